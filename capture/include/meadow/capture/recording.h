#pragma once
// Depth recordings on disk (docs/formats.md#recording): a folder holding recording.json and
// depth/000000.png, depth/000001.png, ... as 16-bit single-channel PNGs in millimetres,
// 0 = no reading. Reading goes through openDepthSource() (depth_source.h); this header holds
// the writer and the small helpers the CLI needs. PNG and JSON details stay in capture/src.
#include <filesystem>
#include <functional>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>
#include <string_view>

#include "meadow/capture/intrinsics.h"
#include "meadow/capture/recording_info.h"

namespace meadow::capture {

// What recording.json says it is; readers reject any other name or version.
inline constexpr std::string_view kRecordingFormatName = "meadow.recording";
inline constexpr int kRecordingFormatVersion = 1;

// Writes a recording folder frame by frame. Every file (each PNG, then recording.json) is
// written to a temporary and renamed, so no half-written file is ever visible. recording.json
// is written last, by finish(): a folder without it is an unfinished recording that readers
// refuse. Frames are always stored in millimetres, whatever info.depthUnit says.
class RecordingWriter {
public:
    // Creates `folder` (and its parents). If `folder` exists it must be empty or a meadow
    // recording (finished or not); its recording.json and depth/ are then removed first.
    // Anything else there throws CaptureError and nothing is touched.
    // Requires info.intrinsics to be usable (Intrinsics::problem() empty) and
    // info.frameRate_hz finite and positive (std::invalid_argument otherwise).
    RecordingWriter(std::filesystem::path folder, RecordingInfo info);
    RecordingWriter(RecordingWriter&&) noexcept;
    RecordingWriter& operator=(RecordingWriter&&) noexcept;
    RecordingWriter(const RecordingWriter&) = delete;
    RecordingWriter& operator=(const RecordingWriter&) = delete;
    // Without finish() the frames stay but recording.json is not written.
    ~RecordingWriter();

    // Appends depth/NNNNNN.png. Requires a frame of info.intrinsics' size and no finish() yet
    // (std::invalid_argument / std::logic_error); throws CaptureError when the disk refuses.
    void write(const cv::Mat1w& depth_mm);
    // Writes recording.json with the final frame count. Requires at least one frame
    // (std::logic_error). Throws CaptureError when the disk refuses.
    void finish();

    [[nodiscard]] int framesWritten() const;
    [[nodiscard]] const std::filesystem::path& folder() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// Whether `folder` may be replaced by a new recording: "" when it does not exist, is empty, or
// holds a meadow recording (finished or not: recording.json, depth/ frames and their
// temporaries) and entries `alsoOurs` accepts; otherwise what is in the way. A writer that
// stages its output (core/staged_folder.h) asks before it starts.
using OurEntry = std::function<bool(const std::filesystem::directory_entry&)>;
[[nodiscard]] std::string whyNotReplaceableRecording(const std::filesystem::path& folder,
                                                     const OurEntry& alsoOurs = {});

// Reads and checks folder/recording.json. Throws CaptureError naming the file and saying what
// to do when the folder or file is missing, the JSON is malformed, the format name or version
// is unknown, or a field is missing, of the wrong type, negative or otherwise unusable.
RecordingInfo readRecordingInfo(const std::filesystem::path& folder);

// Parses the text of --intrinsics, "fx,fy,cx,cy" in pixels (e.g. "525,525,319.5,239.5").
// width_px and height_px are returned as 0: the plain-PNG-folder source takes them from its
// first frame. Throws CaptureError (what was wrong and the expected form) on malformed text,
// a non-finite value or a non-positive focal length.
Intrinsics parseIntrinsics(const std::string& fx_fy_cx_cy);

// True for a frame file name of a recording ("000042.png": six or more digits), or its
// AtomicFile temporary. Label images of synthetic truth follow the same rule.
bool isFrameFileName(std::string_view name);

}  // namespace meadow::capture
