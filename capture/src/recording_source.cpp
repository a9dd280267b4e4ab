#include "recording_source.h"

#include <system_error>

#include "depth_png.h"
#include "meadow/capture/error.h"
#include "meadow/capture/recording.h"
#include "recording_json.h"

namespace meadow::capture::detail {

namespace fs = std::filesystem;

namespace {

std::string sizeText(int width_px, int height_px) {
    return std::to_string(width_px) + "x" + std::to_string(height_px);
}

bool sameFocalAndCentre(const Intrinsics& a, const Intrinsics& b) {
    return a.fx_px == b.fx_px && a.fy_px == b.fy_px && a.cx_px == b.cx_px && a.cy_px == b.cy_px;
}

}  // namespace

cv::Mat1w readFrame_stored(const fs::path& file, const RecordingInfo& info,
                           const std::string& sizeOrigin) {
    cv::Mat1w stored = readDepthPng(file);
    const Intrinsics& k = info.intrinsics;
    if (stored.cols != k.width_px || stored.rows != k.height_px)
        throw CaptureError(file.string() + " is " + sizeText(stored.cols, stored.rows) +
                           " but the frames are " + sizeText(k.width_px, k.height_px) + " (" +
                           sizeOrigin +
                           "): every frame must have the same size; remove or resize it");
    return stored;
}

PngSequenceSource::PngSequenceSource(RecordingInfo info, std::vector<fs::path> frames,
                                     std::string sizeOrigin, cv::Mat1w first_stored)
    : info_(std::move(info)),
      frames_(std::move(frames)),
      sizeOrigin_(std::move(sizeOrigin)),
      first_stored_(std::move(first_stored)) {}

std::optional<DepthFrame> PngSequenceSource::next() {
    if (next_ >= static_cast<int>(frames_.size())) return std::nullopt;
    cv::Mat1w stored;
    if (next_ == 0 && !first_stored_.empty())
        stored = std::move(first_stored_);
    else
        stored = readFrame_stored(frames_[static_cast<std::size_t>(next_)], info_, sizeOrigin_);
    first_stored_.release();
    DepthFrame frame;
    frame.depth_mm = toMillimetres(stored, info_.depthUnit);
    frame.intrinsics = info_.intrinsics;
    frame.index = next_;
    frame.timestamp_s = next_ / info_.frameRate_hz;
    ++next_;
    return frame;
}

std::unique_ptr<DepthSource> openRecordingFolder(const fs::path& folder,
                                                 const SourceOptions& options) {
    const RecordingInfo info = readRecordingInfo(folder);
    const fs::path json = folder / kRecordingJsonName;
    if (options.depthUnit && *options.depthUnit != info.depthUnit)
        throw CaptureError(json.string() + " says the depth unit is " + toString(info.depthUnit) +
                           " but --depth-unit " + toString(*options.depthUnit) +
                           " was given: drop --depth-unit, a recording describes itself");
    if (options.intrinsics && !sameFocalAndCentre(*options.intrinsics, info.intrinsics))
        throw CaptureError(json.string() +
                           " holds other intrinsics than --intrinsics: drop --intrinsics, a "
                           "recording describes itself");

    std::vector<fs::path> frames;
    std::error_code ec;
    for (int i = 0; i < info.frameCount; ++i) {
        fs::path file = framePath(folder, i);
        if (fs::is_directory(file, ec))
            throw CaptureError(file.string() +
                               " is a folder, not a frame: remove it and record "
                               "again, or fix frame_count in " +
                               json.string());
        if (!fs::is_regular_file(file, ec))
            throw CaptureError(file.string() + " is missing but " + json.string() + " says " +
                               std::to_string(info.frameCount) +
                               " frames: the recording is incomplete; record again or fix "
                               "frame_count");
        frames.push_back(std::move(file));
    }
    const std::string sizeOrigin = "from " + json.string();
    cv::Mat1w first = readFrame_stored(frames.front(), info, sizeOrigin);
    return std::make_unique<PngSequenceSource>(info, std::move(frames), sizeOrigin,
                                               std::move(first));
}

}  // namespace meadow::capture::detail
