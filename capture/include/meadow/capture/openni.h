#pragma once
// OpenNI2 conversions and driver discovery that the `meadow convert` command needs. OpenNI2 types
// stay private to capture/.
//
// OpenNI2 finds its drivers in <folder of the libOpenNI2.so.0 that was loaded>/OpenNI2/Drivers
// (lib*.so.0 files). meadow builds a private copy of that layout, with its own driver that
// serves a meadow recording folder as a live device; a process uses it when it starts with
// LD_LIBRARY_PATH=<private folder>/lib (the `meadow` command re-executes itself that way).
#include <filesystem>
#include <functional>
#include <string>

namespace meadow::capture::ni {

// File name of meadow's driver inside a driver folder.
inline constexpr const char* kMeadowDriverFileName = "libMeadowRecordingDevice.so.0";
// Environment variables: where the private driver folder is (overrides the build-tree path),
// and the recording folder meadow's driver lists as its device.
inline constexpr const char* kPrivateFolderVariable = "MEADOW_OPENNI2_DIR";
inline constexpr const char* kRecordingVariable = "MEADOW_OPENNI_RECORDING";

// Folder of the libOpenNI2.so.0 loaded into this process, and the driver folder beside it.
std::filesystem::path loadedLibraryFolder();
std::filesystem::path driverFolder();
// True when meadow's driver sits in driverFolder().
bool meadowDriverInstalled();

// The private driver folder (holding lib/libOpenNI2.so.0 and lib/OpenNI2/Drivers/): the value
// of MEADOW_OPENNI2_DIR if set, else the one the build made. Empty when neither exists.
std::filesystem::path privateFolder();
// One sentence telling a user how to get meadow's driver loaded.
std::string howToLoadMeadowDriver();

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
