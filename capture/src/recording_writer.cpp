#include <cmath>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "depth_png.h"
#include "meadow/capture/error.h"
#include "meadow/capture/recording.h"
#include "meadow/core/atomic_file.h"
#include "recording_json.h"

namespace meadow::capture {

namespace fs = std::filesystem;

namespace {

// Names a recording folder may hold: recording.json, depth/, and the temporaries AtomicFile
// leaves when a process dies between write and rename ("<name>.tmp.<pid>").
bool isRecordingJsonName(const std::string& name) {
    return isFileOrItsTemporary(name, detail::kRecordingJsonName);
}

void writeAtomically(const fs::path& file, std::string_view bytes) {
    try {
        writeFileAtomically(file, bytes);
    } catch (const CaptureError&) {
        throw;
    } catch (const Error& e) {
        throw CaptureError(std::string(e.what()) + " (while writing " + file.string() +
                           "): check free space and permissions");
    }
}

}  // namespace

std::string whyNotReplaceableRecording(const fs::path& folder, const OurEntry& alsoOurs) {
    std::error_code ec;
    const fs::file_status status = fs::status(folder, ec);
    if (!fs::exists(status)) return {};
    if (!fs::is_directory(status)) return folder.string() + " exists and is not a folder";
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name == detail::kDepthFolderName && it->is_directory(ec)) {
            for (fs::directory_iterator f(it->path(), ec); !ec && f != end; f.increment(ec))
                if (!isFrameFileName(f->path().filename().string()))
                    return f->path().string() + " is not a recording frame";
        } else if (!isRecordingJsonName(name) && !(alsoOurs && alsoOurs(*it))) {
            return it->path().string() + " is not part of a recording";
        }
    }
    if (ec) return folder.string() + " cannot be listed (" + ec.message() + ")";
    const fs::path json = folder / detail::kRecordingJsonName;
    if (fs::exists(json, ec) && !detail::isRecordingJson(json))
        return json.string() + " is not a meadow recording.json";
    return {};
}

bool isFrameFileName(std::string_view name) {
    const std::size_t dot = name.find('.');
    constexpr std::size_t kMinDigits = 6;  // depth/000000.png
    if (dot == std::string_view::npos || dot < kMinDigits) return false;
    if (name.substr(0, dot).find_first_not_of("0123456789") != std::string_view::npos) return false;
    return isFileOrItsTemporary(name.substr(dot), ".png");
}

struct RecordingWriter::Impl {
    fs::path folder;
    RecordingInfo info;
    int frames = 0;
    bool finished = false;
};

RecordingWriter::RecordingWriter(fs::path folder, RecordingInfo info)
    : impl_(std::make_unique<Impl>()) {
    if (folder.empty()) throw std::invalid_argument("RecordingWriter: folder is empty");
    if (const std::string problem = info.intrinsics.problem(); !problem.empty())
        throw std::invalid_argument("RecordingWriter: info.intrinsics unusable: " + problem);
    if (!std::isfinite(info.frameRate_hz) || info.frameRate_hz <= 0.0)
        throw std::invalid_argument("RecordingWriter: info.frameRate_hz must be positive, got " +
                                    std::to_string(info.frameRate_hz));
    info.depthUnit = DepthUnit::Millimetre;  // frames are always stored in millimetres
    info.frameCount = 0;

    std::error_code ec;
    const fs::file_status status = fs::status(folder, ec);
    if (fs::exists(status)) {
        if (!fs::is_directory(status))
            throw CaptureError(folder.string() +
                               " exists and is not a folder: choose another recording folder");
        if (const std::string why = whyNotReplaceableRecording(folder); !why.empty())
            throw CaptureError("refusing to overwrite " + folder.string() +
                               ": it is not a meadow recording (" + why +
                               "); choose another folder or remove it first");
        // recording.json first: if we die half-way, what is left is an unfinished recording.
        fs::remove(folder / detail::kRecordingJsonName, ec);
        if (!ec) fs::remove_all(folder / detail::kDepthFolderName, ec);
        if (ec)
            throw CaptureError("cannot clear the old recording in " + folder.string() + ": " +
                               ec.message() + "; check permissions or remove it by hand");
    }
    fs::create_directories(folder / detail::kDepthFolderName, ec);
    if (ec)
        throw CaptureError("cannot create " + (folder / detail::kDepthFolderName).string() + ": " +
                           ec.message() + "; check the path and permissions");
    impl_->folder = std::move(folder);
    impl_->info = std::move(info);
}

RecordingWriter::RecordingWriter(RecordingWriter&&) noexcept = default;
RecordingWriter& RecordingWriter::operator=(RecordingWriter&&) noexcept = default;
RecordingWriter::~RecordingWriter() = default;

void RecordingWriter::write(const cv::Mat1w& depth_mm) {
    if (!impl_) throw std::logic_error("RecordingWriter::write(): moved-from writer");
    if (impl_->finished) throw std::logic_error("RecordingWriter::write(): after finish()");
    const Intrinsics& k = impl_->info.intrinsics;
    if (depth_mm.cols != k.width_px || depth_mm.rows != k.height_px)
        throw std::invalid_argument("RecordingWriter::write(): frame is " +
                                    std::to_string(depth_mm.cols) + "x" +
                                    std::to_string(depth_mm.rows) + ", expected " +
                                    std::to_string(k.width_px) + "x" + std::to_string(k.height_px));
    const fs::path file = detail::framePath(impl_->folder, impl_->frames);
    const std::vector<unsigned char> png = detail::encodeDepthPng(depth_mm, file);
    writeAtomically(file, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    ++impl_->frames;
}

void RecordingWriter::finish() {
    if (!impl_) throw std::logic_error("RecordingWriter::finish(): moved-from writer");
    if (impl_->finished) throw std::logic_error("RecordingWriter::finish(): called twice");
    if (impl_->frames == 0)
        throw std::logic_error("RecordingWriter::finish(): no frame was written");
    impl_->info.frameCount = impl_->frames;
    writeAtomically(impl_->folder / detail::kRecordingJsonName,
                    detail::recordingInfoToJson(impl_->info));
    impl_->finished = true;
}

int RecordingWriter::framesWritten() const { return impl_ ? impl_->frames : 0; }

const fs::path& RecordingWriter::folder() const {
    if (!impl_) throw std::logic_error("RecordingWriter::folder(): moved-from writer");
    return impl_->folder;
}

}  // namespace meadow::capture
