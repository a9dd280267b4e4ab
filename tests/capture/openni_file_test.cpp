// .oni files played through OpenNI2's own file driver: a real Kinect-class recording gives the
// facts its README states, and broken files give one clear CaptureError, never a crash.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <vector>

#include "meadow/capture/depth_source.h"
#include "meadow/capture/error.h"
#include "support/shared_data.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
using namespace meadow::capture;

namespace {

const fs::path kRealOni = meadow::test::realOniRecording();

fs::path freshDir(const std::string& name) { return meadow::test::freshTempDir("openni_" + name); }

void writeBytes(const fs::path& file, const std::vector<char>& bytes) {
    std::ofstream out(file, std::ios::binary);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::vector<char> readBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Opens `uri` and reads it to the end; returns the CaptureError text, or "" if none was thrown.
std::string errorWhilePlaying(const std::string& uri) {
    try {
        auto source = openDepthSource(uri);
        while (source->next()) {
        }
    } catch (const CaptureError& e) {
        return e.what();
    }
    return {};
}

}  // namespace

TEST(OpenNiFile, RealRecordingPlaysWithTheFactsOfItsReadme) {
    if (!fs::exists(kRealOni)) GTEST_SKIP() << "shared data absent: " << kRealOni;
    auto source = openDepthSource(kRealOni.string());
    const RecordingInfo& info = source->info();
    EXPECT_EQ(info.frameCount, 12);
    EXPECT_EQ(info.intrinsics.width_px, 640);
    EXPECT_EQ(info.intrinsics.height_px, 480);
    // hFOV 1.0145 rad, vFOV 0.7898 rad -> fx = fy = 575.8 px, centre (319.5, 239.5).
    EXPECT_NEAR(info.intrinsics.fx_px, 575.8f, 0.1f);
    EXPECT_NEAR(info.intrinsics.fy_px, 575.8f, 0.1f);
    EXPECT_FLOAT_EQ(info.intrinsics.cx_px, 319.5f);
    EXPECT_FLOAT_EQ(info.intrinsics.cy_px, 239.5f);
    EXPECT_DOUBLE_EQ(info.frameRate_hz, 30.0);
    EXPECT_EQ(info.depthUnit, DepthUnit::Millimetre);

    int frames = 0;
    double smallest_mm = 1e9, largest_mm = 0, previousTime_s = -1;
    std::vector<cv::Mat1w> seen;
    while (auto frame = source->next()) {
        EXPECT_EQ(frame->index, frames);
        ASSERT_EQ(frame->depth_mm.cols, 640);
        ASSERT_EQ(frame->depth_mm.rows, 480);
        EXPECT_EQ(frame->intrinsics, info.intrinsics);
        EXPECT_GT(frame->timestamp_s, previousTime_s) << "frame " << frames;
        previousTime_s = frame->timestamp_s;
        const double zeros =
            1.0 - cv::countNonZero(frame->depth_mm) / static_cast<double>(frame->depth_mm.total());
        EXPECT_NEAR(zeros, 0.23, 0.02) << "frame " << frames;  // "~23 % no data"
        double lo = 0, hi = 0;
        cv::minMaxLoc(frame->depth_mm, &lo, &hi, nullptr, nullptr, frame->depth_mm > 0);
        smallest_mm = std::min(smallest_mm, lo);
        largest_mm = std::max(largest_mm, hi);
        for (const auto& earlier : seen)  // "all 12 frames differ (live sensor noise)"
            EXPECT_GT(cv::norm(earlier, frame->depth_mm, cv::NORM_L1), 0.0) << "frame " << frames;
        seen.push_back(frame->depth_mm.clone());
        ++frames;
    }
    EXPECT_EQ(frames, 12);
    EXPECT_EQ(smallest_mm, 626);  // "valid range 626..4581 mm"
    EXPECT_EQ(largest_mm, 4581);
    // Timestamps 11680..378742 us in the file.
    EXPECT_NEAR(previousTime_s, 0.378742, 1e-6);
    EXPECT_FALSE(source->next()) << "the end stays the end";
}

TEST(OpenNiFile, OpeningAgainPlaysFromTheFirstFrame) {
    if (!fs::exists(kRealOni)) GTEST_SKIP() << "shared data absent: " << kRealOni;
    cv::Mat1w firstOfFirstRun;
    {
        auto source = openDepthSource(kRealOni.string());
        firstOfFirstRun = source->next()->depth_mm.clone();
        ASSERT_TRUE(source->next());  // leave it mid-way
    }
    // A new source opens the file anew (no seek: it crashes Debian's file driver).
    auto again = openDepthSource(kRealOni.string());
    auto first = again->next();
    ASSERT_TRUE(first);
    EXPECT_EQ(first->index, 0);
    EXPECT_EQ(cv::norm(first->depth_mm, firstOfFirstRun, cv::NORM_INF), 0.0);
}

TEST(OpenNiFile, SameFileTwiceAtOnceIsOneClearErrorAndAfterwardsFine) {
    if (!fs::exists(kRealOni)) GTEST_SKIP() << "shared data absent: " << kRealOni;
    {
        auto first = openDepthSource(kRealOni.string());
        // OpenNI2 hands one player per file to every opener: a second source would steal frames.
        try {
            openDepthSource(kRealOni.string());
            ADD_FAILURE() << "opened the same file twice at once";
        } catch (const CaptureError& e) {
            EXPECT_NE(std::string(e.what()).find("twice"), std::string::npos) << e.what();
        }
        int frames = 0;
        while (first->next()) ++frames;
        EXPECT_EQ(frames, 12) << "the refused second opener did not disturb the first";
    }
    auto again = openDepthSource(kRealOni.string());
    EXPECT_TRUE(again->next());
}

TEST(OpenNiFile, RandomBytesAreOneClearError) {
    const fs::path dir = freshDir("corrupt");
    const fs::path file = dir / "noise.oni";
    std::mt19937 rng(7);
    std::vector<char> bytes(64 * 1024);
    for (char& b : bytes) b = static_cast<char>(rng());
    writeBytes(file, bytes);
    const std::string error = errorWhilePlaying(file.string());
    EXPECT_NE(error.find(file.string()), std::string::npos) << error;
    EXPECT_NE(error.find("not a complete .oni"), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
    fs::remove_all(dir);
}

TEST(OpenNiFile, FirstHalfOfARealFileIsOneClearError) {
    if (!fs::exists(kRealOni)) GTEST_SKIP() << "shared data absent: " << kRealOni;
    const fs::path dir = freshDir("truncated");
    const fs::path file = dir / "half.oni";
    std::vector<char> bytes = readBytes(kRealOni);
    bytes.resize(bytes.size() / 2);  // as if the recorder died mid-way: no index, no end record
    writeBytes(file, bytes);
    const std::string error = errorWhilePlaying(file.string());
    EXPECT_NE(error.find(file.string()), std::string::npos) << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
    fs::remove_all(dir);
}

TEST(OpenNiFile, MissingFileIsNamed) {
    const std::string missing = "/nonexistent/meadow/recording.oni";
    const std::string error = errorWhilePlaying(missing);
    EXPECT_NE(error.find(missing), std::string::npos) << error;
    EXPECT_NE(error.find("no such file"), std::string::npos) << error;
}

TEST(OpenNiFile, EmptyFileIsOneClearError) {
    const fs::path dir = freshDir("empty");
    const fs::path file = dir / "empty.oni";
    writeBytes(file, {});
    const std::string error = errorWhilePlaying(file.string());
    EXPECT_NE(error.find(file.string()), std::string::npos) << error;
    fs::remove_all(dir);
}
