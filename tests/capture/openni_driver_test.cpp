// meadow's OpenNI2 driver: a recording folder served as a live OpenNI2 device, and the
// conversions built on it (folder -> .oni -> folder). OpenNI2 only loads the driver in a process
// started with LD_LIBRARY_PATH=<build>/openni2/lib, so each OpenNiDriver test re-runs this
// program with that environment and the matching OpenNiDriverChild test; the child tests skip
// when run on their own.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "meadow/capture/depth_source.h"
#include "meadow/capture/error.h"
#include "meadow/capture/recording.h"
#include "openni_convert.h"  // private to capture/, tested here
#include "support/shared_data.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
using namespace meadow::capture;

namespace {

const fs::path kPrivateFolder = fs::path(MEADOW_BINARY_DIR) / "openni2";
const fs::path kRealOni = meadow::test::realOniRecording();
constexpr const char* kChildVariable = "MEADOW_OPENNI_TEST_CHILD";

bool inChild() { return std::getenv(kChildVariable) != nullptr; }

fs::path freshDir(const std::string& name) { return meadow::test::freshTempDir("openni_" + name); }

RecordingInfo syntheticInfo(int frames) {
    RecordingInfo info;
    info.sensor = "synthetic";
    info.intrinsics = {.width_px = 64,
                       .height_px = 48,
                       .fx_px = 57.58f,
                       .fy_px = 57.58f,
                       .cx_px = 31.5f,
                       .cy_px = 23.5f};
    info.frameCount = frames;
    info.frameRate_hz = 30.0;
    return info;
}

// Frame i: a ramp over the image that differs per frame, full 16-bit range used (1..65534),
// plus a block of zeros (no reading) that moves.
cv::Mat1w syntheticFrame(int i, const Intrinsics& k) {
    cv::Mat1w depth_mm(k.height_px, k.width_px);
    for (int y = 0; y < k.height_px; ++y)
        for (int x = 0; x < k.width_px; ++x)
            depth_mm(y, x) =
                static_cast<std::uint16_t>(1 + (x * 997 + y * 7919 + i * 104729) % 65534);
    depth_mm(cv::Rect(i * 3, 5, 10, 8)) = 0;
    return depth_mm;
}

void writeSyntheticRecording(const fs::path& folder, int frames) {
    const RecordingInfo info = syntheticInfo(frames);
    RecordingWriter writer(folder, info);
    for (int i = 0; i < frames; ++i) writer.write(syntheticFrame(i, info.intrinsics));
    writer.finish();
}

// Every frame of both sources equal bit for bit; intrinsics equal within float round-off of
// the field-of-view round trip.
void expectSameRecording(const std::string& expectedUri, const std::string& actualUri) {
    auto expected = openDepthSource(expectedUri);
    auto actual = openDepthSource(actualUri);
    const Intrinsics& a = expected->info().intrinsics;
    const Intrinsics& b = actual->info().intrinsics;
    EXPECT_EQ(b.width_px, a.width_px);
    EXPECT_EQ(b.height_px, a.height_px);
    EXPECT_NEAR(b.fx_px, a.fx_px, 1e-3f * a.fx_px);
    EXPECT_NEAR(b.fy_px, a.fy_px, 1e-3f * a.fy_px);
    EXPECT_FLOAT_EQ(b.cx_px, a.cx_px);
    EXPECT_FLOAT_EQ(b.cy_px, a.cy_px);
    int frames = 0;
    while (auto e = expected->next()) {
        auto f = actual->next();
        ASSERT_TRUE(f) << actualUri << " ends after " << frames << " frames";
        EXPECT_EQ(f->index, e->index);
        EXPECT_EQ(cv::norm(e->depth_mm, f->depth_mm, cv::NORM_INF), 0.0)
            << "frame " << frames << " of " << actualUri;
        ++frames;
    }
    EXPECT_FALSE(actual->next()) << actualUri << " has more than " << frames << " frames";
    EXPECT_GT(frames, 0);
}

// Runs this test program again with `environment` (NAME=value ...) for one child test.
meadow::test::CommandResult runChild(const std::string& childTest, const std::string& environment) {
    std::array<char, 4096> self{};
    const ssize_t n = ::readlink("/proc/self/exe", self.data(), self.size() - 1);
    if (n <= 0) return {};
    const std::string command = "env " + std::string(kChildVariable) + "=1 " + environment + " '" +
                                std::string(self.data(), static_cast<std::size_t>(n)) +
                                "' --gtest_filter=OpenNiDriverChild." + childTest;
    return meadow::test::runCommand(command);
}

#define SKIP_UNLESS_PRIVATE_FOLDER()                                                       \
    if (!fs::exists(kPrivateFolder / "lib/OpenNI2/Drivers/libMeadowRecordingDevice.so.0")) \
    GTEST_SKIP() << "no private OpenNI2 folder at " << kPrivateFolder                      \
                 << ": build the target meadow_openni2_folder"

// Runs OpenNiDriverChild.NAME with meadow's driver loaded and expects it to pass.
#define EXPECT_CHILD_PASSES(NAME, EXTRA_ENV)                                                    \
    do {                                                                                        \
        const meadow::test::CommandResult child = runChild(                                     \
            NAME, "LD_LIBRARY_PATH=" + (kPrivateFolder / "lib").string() + " " + EXTRA_ENV);    \
        EXPECT_EQ(child.exitCode, 0) << child.output;                                           \
        EXPECT_NE(child.output.find("[  PASSED  ] 1 test"), std::string::npos) << child.output; \
    } while (false)

#define CHILD_ONLY() \
    if (!inChild()) GTEST_SKIP() << "runs inside OpenNiDriver tests, with meadow's driver loaded"

}  // namespace

// ---- In this process: meadow's driver is not loaded here ------------------------------------

TEST(OpenNiDriver, RecordingUriWithoutTheDriverIsOneClearError) {
    if (inChild()) GTEST_SKIP();
    const fs::path dir = freshDir("nodriver");
    writeSyntheticRecording(dir / "rec", 2);
    try {
        openDepthSource("openni://" + (dir / "rec").string());
        ADD_FAILURE() << "opened a recording folder without meadow's driver";
    } catch (const CaptureError& e) {
        const std::string text = e.what();
        EXPECT_NE(text.find("LD_LIBRARY_PATH"), std::string::npos) << text;
        EXPECT_NE(text.find((dir / "rec").string()), std::string::npos) << text;
    }
    fs::remove_all(dir);
}

// ---- Parents: run the child tests below with meadow's private OpenNI2 folder ----------------

TEST(OpenNiDriver, LiveDeviceDeliversTheRecordingsFrames) {
    SKIP_UNLESS_PRIVATE_FOLDER();
    EXPECT_CHILD_PASSES("LiveDeviceDeliversTheRecordingsFrames", "");
}
TEST(OpenNiDriver, AnyDeviceIsTheRecordingNamedByTheEnvironment) {
    SKIP_UNLESS_PRIVATE_FOLDER();
    const fs::path dir = freshDir("anydevice");
    writeSyntheticRecording(dir / "rec", 3);
    EXPECT_CHILD_PASSES("AnyDeviceIsTheRecordingNamedByTheEnvironment",
                        "MEADOW_OPENNI_RECORDING=" + (dir / "rec").string());
    fs::remove_all(dir);
}
TEST(OpenNiDriver, FolderToOniToFolderIsBitIdentical) {
    SKIP_UNLESS_PRIVATE_FOLDER();
    EXPECT_CHILD_PASSES("FolderToOniToFolderIsBitIdentical", "");
}
TEST(OpenNiDriver, RealOniToFolderToOniToFolderIsBitIdentical) {
    SKIP_UNLESS_PRIVATE_FOLDER();
    if (!fs::exists(kRealOni)) GTEST_SKIP() << "shared data absent: " << kRealOni;
    EXPECT_CHILD_PASSES("RealOniToFolderToOniToFolderIsBitIdentical", "");
}
TEST(OpenNiDriver, BrokenRecordingIsOneClearError) {
    SKIP_UNLESS_PRIVATE_FOLDER();
    EXPECT_CHILD_PASSES("BrokenRecordingIsOneClearError", "");
}
TEST(OpenNiDriver, MissingDriverFolderIsOneClearError) {
    SKIP_UNLESS_PRIVATE_FOLDER();
    // The child opens the real recording; without it the child skips, and its "[  SKIPPED ]"
    // line would have ctest report this test's failed expectations as a skip.
    if (!fs::exists(kRealOni)) GTEST_SKIP() << "shared data absent: " << kRealOni;
    // A library folder with OpenNI2 but no OpenNI2/Drivers beside it.
    const fs::path dir = freshDir("nodrivers");
    fs::copy_file(kPrivateFolder / "lib/libOpenNI2.so.0", dir / "libOpenNI2.so.0");
    const meadow::test::CommandResult child =
        runChild("MissingDriverFolderIsOneClearError", "LD_LIBRARY_PATH=" + dir.string());
    EXPECT_EQ(child.exitCode, 0) << child.output;
    EXPECT_NE(child.output.find("[  PASSED  ] 1 test"), std::string::npos) << child.output;
    fs::remove_all(dir);
}

// ---- Children: run with LD_LIBRARY_PATH=<build>/openni2/lib ----------------------------------

TEST(OpenNiDriverChild, LiveDeviceDeliversTheRecordingsFrames) {
    CHILD_ONLY();
    const fs::path dir = freshDir("live");
    const fs::path folder = dir / "rec";
    writeSyntheticRecording(folder, 5);
    auto device = openDepthSource("openni://" + folder.string());
    const RecordingInfo& info = device->info();
    EXPECT_EQ(info.sensor, "openni2:meadow/Recording");
    EXPECT_EQ(info.frameCount, 5) << "the driver tells how long the recording is";
    EXPECT_NEAR(info.intrinsics.fx_px, 57.58f, 1e-3f);
    EXPECT_FLOAT_EQ(info.intrinsics.cx_px, 31.5f);
    int frames = 0;
    while (auto frame = device->next()) {
        EXPECT_EQ(frame->index, frames);
        EXPECT_NEAR(frame->timestamp_s, frames / 30.0, 1e-6);
        EXPECT_EQ(cv::norm(frame->depth_mm, syntheticFrame(frames, info.intrinsics), cv::NORM_INF),
                  0.0)
            << "frame " << frames;
        ++frames;
    }
    EXPECT_EQ(frames, 5);
    fs::remove_all(dir);
}

TEST(OpenNiDriverChild, AnyDeviceIsTheRecordingNamedByTheEnvironment) {
    CHILD_ONLY();
    auto device = openDepthSource("openni://");
    EXPECT_EQ(device->info().sensor, "openni2:meadow/Recording");
    int frames = 0;
    while (auto frame = device->next()) {
        EXPECT_EQ(cv::norm(frame->depth_mm, syntheticFrame(frames, device->info().intrinsics),
                           cv::NORM_INF),
                  0.0);
        ++frames;
    }
    EXPECT_EQ(frames, 3);
}

TEST(OpenNiDriverChild, FolderToOniToFolderIsBitIdentical) {
    CHILD_ONLY();
    const fs::path dir = freshDir("roundtrip");
    writeSyntheticRecording(dir / "rec", 6);
    EXPECT_EQ(ni::recordingToOni(dir / "rec", dir / "rec.oni"), 6);
    EXPECT_EQ(ni::oniToRecording(dir / "rec.oni", dir / "back"), 6);
    expectSameRecording((dir / "rec").string(), (dir / "rec.oni").string());
    expectSameRecording((dir / "rec").string(), (dir / "back").string());
    for (const auto& entry : fs::directory_iterator(dir))  // no temporaries left behind
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    fs::remove_all(dir);
}

TEST(OpenNiDriverChild, RealOniToFolderToOniToFolderIsBitIdentical) {
    CHILD_ONLY();
    const fs::path dir = freshDir("realtrip");
    EXPECT_EQ(ni::oniToRecording(kRealOni, dir / "room"), 12);
    EXPECT_EQ(ni::recordingToOni(dir / "room", dir / "room.oni"), 12);
    EXPECT_EQ(ni::oniToRecording(dir / "room.oni", dir / "again"), 12);
    expectSameRecording(kRealOni.string(), (dir / "room").string());
    expectSameRecording((dir / "room").string(), (dir / "again").string());
    fs::remove_all(dir);
}

TEST(OpenNiDriverChild, BrokenRecordingIsOneClearError) {
    CHILD_ONLY();
    const fs::path dir = freshDir("broken");
    writeSyntheticRecording(dir / "rec", 4);
    fs::remove(dir / "rec/depth/000002.png");  // a frame gone missing after recording
    try {
        ni::recordingToOni(dir / "rec", dir / "rec.oni");
        ADD_FAILURE() << "converted a recording with a missing frame";
    } catch (const CaptureError& e) {
        const std::string text = e.what();
        EXPECT_NE(text.find("000002.png"), std::string::npos) << text;
        EXPECT_EQ(text.find('\n'), std::string::npos) << text;
    }
    EXPECT_FALSE(fs::exists(dir / "rec.oni")) << "no partial output";
    for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    fs::remove_all(dir);
}

TEST(OpenNiDriverChild, MissingDriverFolderIsOneClearError) {
    CHILD_ONLY();
    if (!fs::exists(kRealOni)) GTEST_SKIP() << "shared data absent: " << kRealOni;
    try {
        openDepthSource(kRealOni.string());
        ADD_FAILURE() << "played a file with no OpenNI2 driver folder";
    } catch (const CaptureError& e) {
        const std::string text = e.what();
        EXPECT_NE(text.find("driver folder"), std::string::npos) << text;
        EXPECT_NE(text.find("OpenNI2/Drivers"), std::string::npos) << text;
    }
}
