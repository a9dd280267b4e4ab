#pragma once
// Where the test programs find the real recordings of ../shared/data (read-only input, never
// copied into the repository). MEADOW_SHARED_DATA_DIR is set for every test suite
// (cmake/MeadowLayer.cmake); a test that needs a file skips when it is absent.
#include <filesystem>

namespace meadow::test {

// ../shared/data itself.
inline std::filesystem::path sharedDataDir() { return MEADOW_SHARED_DATA_DIR; }

// The real Kinect recording (real/oni-3dj-room, its README.txt beside it).
inline std::filesystem::path realOniRecording() {
    return std::filesystem::path(MEADOW_SHARED_DATA_DIR) / "real/oni-3dj-room/test.oni";
}

}  // namespace meadow::test
