// A plain folder of 16-bit depth PNGs from another tool (e.g. TUM RGB-D), read in name order.
#include <system_error>

#include "depth_png.h"
#include "meadow/capture/error.h"
#include "recording_json.h"
#include "recording_source.h"

namespace meadow::capture::detail {

namespace fs = std::filesystem;

namespace {
// A plain folder carries no frame rate; frames are timed as if captured at this rate.
constexpr double kPlainFolderFrameRate_hz = 30.0;
const char* kPlainFolderSensor = "png-folder";
}  // namespace

std::unique_ptr<DepthSource> openPngFolder(const fs::path& folder, const SourceOptions& options) {
    std::vector<fs::path> frames = listPngFiles(folder);
    if (frames.empty()) {
        std::error_code ec;
        const fs::path depth = folder / kDepthFolderName;
        if (fs::is_directory(depth, ec) && !listPngFiles(depth).empty())
            throw CaptureError((folder / kRecordingJsonName).string() +
                               " is missing: the recording was not finished; record again, or "
                               "read its frames as a plain folder: " +
                               depth.string() + " --intrinsics fx,fy,cx,cy --depth-unit mm");
        throw CaptureError(folder.string() +
                           " holds no recording.json and no .png frames: give a meadow "
                           "recording folder or a folder of 16-bit depth PNGs");
    }
    if (!options.intrinsics || !options.depthUnit)
        throw CaptureError((folder / kRecordingJsonName).string() + " is missing, so the " +
                           std::to_string(frames.size()) +
                           " PNGs there are read as a plain folder, which needs the camera: "
                           "pass --intrinsics fx,fy,cx,cy and --depth-unit mm|0.2mm|m");

    RecordingInfo info;
    info.sensor = kPlainFolderSensor;
    info.depthUnit = *options.depthUnit;
    info.frameCount = static_cast<int>(frames.size());
    info.frameRate_hz = kPlainFolderFrameRate_hz;
    info.intrinsics = *options.intrinsics;

    cv::Mat1w first = readDepthPng(frames.front());
    info.intrinsics.width_px = first.cols;
    info.intrinsics.height_px = first.rows;
    if (const std::string problem = info.intrinsics.problem(); !problem.empty())
        throw CaptureError("--intrinsics for " + folder.string() + " are unusable: " + problem +
                           "; pass --intrinsics fx,fy,cx,cy in pixels");
    const std::string sizeOrigin = "from the first frame, " + frames.front().filename().string();
    return std::make_unique<PngSequenceSource>(info, std::move(frames), sizeOrigin,
                                               std::move(first));
}

}  // namespace meadow::capture::detail
