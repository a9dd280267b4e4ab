#include "depth_png.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <system_error>

#include "meadow/capture/error.h"
#include "meadow/core/library_messages.h"

namespace meadow::capture::detail {

namespace fs = std::filesystem;

namespace {

// The 8-byte signature every PNG starts with (PNG spec, Sec. 5.2).
constexpr std::array<unsigned char, 8> kPngSignature = {0x89, 'P',  'N',  'G',
                                                        '\r', '\n', 0x1A, '\n'};
// Every complete PNG ends with an empty IEND chunk: length 0, type "IEND", CRC AE 42 60 82.
constexpr std::array<unsigned char, 12> kPngEnd = {0,   0,   0,    0,    'I',  'E',
                                                   'N', 'D', 0xAE, 0x42, 0x60, 0x82};
// Largest stored value in metres that still fits in 16-bit millimetres (65 m -> 65000 mm).
constexpr int kMaxMetresIn16BitMillimetres = 65;

const char* kFrameFormatHint =
    "depth frames must be 16-bit single-channel PNGs (millimetres, or the unit given by "
    "--depth-unit)";

std::string describeType(const cv::Mat& image) {
    const int bits = image.depth() == CV_8U || image.depth() == CV_8S     ? 8
                     : image.depth() == CV_16U || image.depth() == CV_16S ? 16
                                                                          : 32;
    const std::string kind = image.channels() == 1   ? "single-channel"
                             : image.channels() == 2 ? "grey+alpha"
                             : image.channels() == 3 ? "colour (3-channel)"
                                                     : "colour (4-channel)";
    return std::to_string(bits) + "-bit " + kind;
}

}  // namespace

std::vector<unsigned char> encodeDepthPng(const cv::Mat1w& depth, const fs::path& forFile) {
    std::vector<unsigned char> bytes;
    bool ok = false;
    try {
        ok = cv::imencode(".png", depth, bytes);
    } catch (const cv::Exception& e) {
        throw CaptureError("cannot encode " + forFile.string() + " as PNG: " + e.what());
    }
    if (!ok) throw CaptureError("cannot encode " + forFile.string() + " as PNG");
    return bytes;
}

cv::Mat1w readDepthPng(const fs::path& file) {
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    if (!in)
        throw CaptureError("cannot read " + file.string() +
                           ": check that it exists and is readable");
    const std::streamoff size = in.tellg();
    std::vector<unsigned char> bytes(size > 0 ? static_cast<std::size_t>(size) : 0);
    in.seekg(0);
    if (!bytes.empty() &&
        !in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
        throw CaptureError("reading " + file.string() + " failed: check the disk and retry");
    return decodeDepthPng(bytes, file);
}

cv::Mat1w decodeDepthPng(const std::vector<unsigned char>& bytes, const fs::path& file) {
    if (bytes.empty())
        throw CaptureError(file.string() +
                           " is empty (0 bytes): the frame was never written completely; "
                           "remove it or record again");
    if (bytes.size() < kPngSignature.size() ||
        !std::equal(kPngSignature.begin(), kPngSignature.end(), bytes.begin()))
        throw CaptureError(file.string() +
                           " is not a PNG file (no PNG signature): " + kFrameFormatHint);
    // A file cut short loses its end marker; some decoders still hand back a partial image.
    const bool complete = std::search(bytes.begin() + kPngSignature.size(), bytes.end(),
                                      kPngEnd.begin(), kPngEnd.end()) != bytes.end();

    // Checked before decoding, so the decoder never sees a file that is cut short.
    if (!complete)
        throw CaptureError(file.string() +
                           " is truncated (it does not end with the PNG end marker): re-export "
                           "the frame or remove it from the folder");
    cv::Mat decoded;
    CapturedStderr libpng;  // what libpng says of a corrupt file belongs in our one line
    try {
        decoded = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception&) {
        decoded.release();  // reported below like any other undecodable file
    }
    const std::string said = libpng.text();
    if (decoded.empty())
        throw CaptureError(file.string() + " is corrupt (" +
                           (said.empty() ? std::string("OpenCV cannot decode it") : said) +
                           "): re-export the frame or remove it from the folder");
    if (decoded.type() != CV_16UC1)
        throw CaptureError(file.string() + (decoded.depth() == CV_8U ? " is an " : " is a ") +
                           describeType(decoded) + " PNG, but " + kFrameFormatHint +
                           ": export the depth as 16-bit greyscale");
    return decoded;
}

cv::Mat1w toMillimetres(const cv::Mat1w& stored, DepthUnit unit) {
    cv::Mat1w depth_mm;
    switch (unit) {
        case DepthUnit::Millimetre:
            depth_mm = stored.clone();
            break;
        case DepthUnit::FifthMillimetre:
            // v * 0.2 has fractional part .0/.2/.4/.6/.8, so rounding never meets a tie.
            stored.convertTo(depth_mm, CV_16U, millimetresPerUnit(unit));
            break;
        case DepthUnit::Metre: {
            cv::Mat1w fits;
            stored.copyTo(fits);
            fits.setTo(0, stored > kMaxMetresIn16BitMillimetres);
            fits.convertTo(depth_mm, CV_16U, millimetresPerUnit(unit));
            break;
        }
    }
    return depth_mm;
}

bool hasPngExtension(const fs::path& file) {
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".png";
}

std::vector<fs::path> listPngFiles(const fs::path& folder) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code typeEc;
        if (it->is_regular_file(typeEc) && hasPngExtension(it->path())) files.push_back(it->path());
    }
    if (ec)
        throw CaptureError("cannot list " + folder.string() + ": " + ec.message() +
                           ": check that it is a readable folder");
    std::sort(files.begin(), files.end(),
              [](const fs::path& a, const fs::path& b) { return a.filename() < b.filename(); });
    return files;
}

}  // namespace meadow::capture::detail
