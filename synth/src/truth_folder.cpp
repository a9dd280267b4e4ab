#include "truth_folder.h"

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <string_view>
#include <system_error>
#include <vector>

#include "meadow/capture/recording.h"
#include "meadow/core/atomic_file.h"
#include "meadow/core/temporaries.h"
#include "meadow/synth/error.h"

namespace meadow::synth::detail {
namespace fs = std::filesystem;
namespace {

// What meadow synth writes into truth/ besides labels/.
constexpr const char* kTruthFileNames[] = {"blades.json", "plant.json"};
// Label images are mostly 0: the slowest, smallest PNG setting costs little here.
constexpr int kLabelPngCompression = 9;

bool isTruthFile(const std::string& name) {
    for (const char* file : kTruthFileNames)
        if (isFileOrItsTemporary(name, file)) return true;
    return false;
}

// The first entry of a truth folder that meadow synth did not write ("" for none), so replacing
// it never deletes anything else.
std::string foreignTruthEntry(const fs::path& folder) {
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name == kLabelsFolderName && it->is_directory(ec)) {
            for (fs::directory_iterator f(it->path(), ec); !ec && f != end; f.increment(ec))
                if (!capture::isFrameFileName(f->path().filename().string()))
                    return f->path().string();
        } else if (!isTruthFile(name)) {
            return it->path().string();
        }
    }
    return ec ? folder.string() : std::string();
}

// The truth a previous synth run left beside its recording belongs to the recording it replaces.
bool isOldTruth(const fs::directory_entry& entry) {
    std::error_code ec;
    return entry.path().filename() == kTruthFolderName && entry.is_directory(ec) &&
           foreignTruthEntry(entry.path()).empty();
}

}  // namespace

std::string labelsPath(int frameIndex) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.png", frameIndex);
    return std::string(kLabelsFolderName) + "/" + name;
}

void writeLabels(const fs::path& file, const cv::Mat1w& labels) {
    std::vector<unsigned char> bytes;
    if (!cv::imencode(".png", labels, bytes, {cv::IMWRITE_PNG_COMPRESSION, kLabelPngCompression}))
        throw SynthError("cannot encode the label image " + file.string() +
                         " as PNG: check the OpenCV build has PNG support");
    writeFileAtomically(
        file, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void checkReplaceableSynthOutput(const fs::path& out) {
    std::error_code ec;
    if (fs::is_directory(out / kTruthFolderName, ec))
        if (const std::string foreign = foreignTruthEntry(out / kTruthFolderName); !foreign.empty())
            throw SynthError("refusing to overwrite " + out.string() + ": its truth holds " +
                             foreign +
                             ", which meadow synth did not write; choose another --out folder "
                             "or remove it first");
    if (const std::string why = capture::whyNotReplaceableRecording(out, isOldTruth); !why.empty())
        throw SynthError("refusing to overwrite " + out.string() +
                         ": it is not a meadow recording (" + why +
                         "); choose another --out folder or remove it first");
}

}  // namespace meadow::synth::detail
