#pragma once
// Conversions between meadow recording folders and OpenNI .oni files (private to capture/; the
// `meadow convert` command is their only user). Both write their output whole or not at all:
// into a temporary beside it, renamed into place once complete.
#include <filesystem>
#include <functional>

namespace meadow::capture::ni {

// Called after each frame with the frames done so far and the total (0 when unknown).
using FrameProgress = std::function<void(int framesDone, int framesTotal)>;

// Serves `recordingFolder` through meadow's OpenNI2 driver and records its depth stream with
// openni::Recorder into `oniPath` (lossless 16z depth, as a camera recording would be). Needs
// meadow's driver loaded in this process (meadowDriverInstalled()); throws CaptureError
// otherwise, or when the recording, the recorder or the disk fails. Returns frames written.
int recordingToOni(const std::filesystem::path& recordingFolder,
                   const std::filesystem::path& oniPath, const FrameProgress& progress = {});

// Plays `oniPath` through OpenNI2 and writes its depth frames as a meadow recording folder.
// An existing `folder` must be empty or a meadow recording; it is replaced only once the new
// recording is complete. Throws CaptureError. Returns frames written.
int oniToRecording(const std::filesystem::path& oniPath, const std::filesystem::path& folder,
                   const FrameProgress& progress = {});

}  // namespace meadow::capture::ni
