#pragma once
// Private: depth sources that read 16-bit PNG frames from disk. A recording folder
// (recording.json + depth/NNNNNN.png) and a plain folder of PNGs differ only in where the
// RecordingInfo comes from; both then play frames the same way.
#include <filesystem>
#include <memory>
#include <vector>

#include "meadow/capture/depth_source.h"

namespace meadow::capture::detail {

// Plays `frames` in order, converting `info.depthUnit` to millimetres. Every frame must be
// info.intrinsics' size; `sizeOrigin` says where that size came from, for messages.
// `first_stored` is frames[0] already decoded (stored units), or empty.
class PngSequenceSource final : public DepthSource {
public:
    PngSequenceSource(RecordingInfo info, std::vector<std::filesystem::path> frames,
                      std::string sizeOrigin, cv::Mat1w first_stored = {});
    [[nodiscard]] const RecordingInfo& info() const override { return info_; }
    std::optional<DepthFrame> next() override;

private:
    RecordingInfo info_;
    std::vector<std::filesystem::path> frames_;
    std::string sizeOrigin_;
    cv::Mat1w first_stored_;
    int next_ = 0;
};

// Reads a frame file and checks its size against `info` (CaptureError naming the file).
cv::Mat1w readFrame_stored(const std::filesystem::path& file, const RecordingInfo& info,
                           const std::string& sizeOrigin);

// A folder with recording.json. Options, where given, must agree with it.
std::unique_ptr<DepthSource> openRecordingFolder(const std::filesystem::path& folder,
                                                 const SourceOptions& options);
// A folder of 16-bit PNGs without recording.json; needs options.intrinsics and
// options.depthUnit. Width and height come from the first frame.
std::unique_ptr<DepthSource> openPngFolder(const std::filesystem::path& folder,
                                           const SourceOptions& options);

}  // namespace meadow::capture::detail
