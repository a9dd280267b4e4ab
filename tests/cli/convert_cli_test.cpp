// `meadow convert` as a user runs it: the real binary (which restarts itself with meadow's
// OpenNI2 driver when it needs it), real files, exit codes and one-line messages.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <random>
#include <string>

#include "cli_test_util.h"
#include "meadow/capture/depth_source.h"
#include "meadow/capture/recording.h"
#include "support/shared_data.h"

namespace fs = std::filesystem;
using namespace meadow::capture;
using meadow::test::countLines;
using meadow::test::freshTempDir;
using meadow::test::runMeadow;

namespace {

const fs::path kRealOni = meadow::test::realOniRecording();

void writeRecording(const fs::path& folder, int frames) {
    RecordingInfo info;
    info.sensor = "synthetic";
    info.intrinsics = {.width_px = 40,
                       .height_px = 30,
                       .fx_px = 36.f,
                       .fy_px = 36.f,
                       .cx_px = 19.5f,
                       .cy_px = 14.5f};
    info.frameCount = frames;
    RecordingWriter writer(folder, info);
    std::mt19937 rng(11);
    for (int i = 0; i < frames; ++i) {
        cv::Mat1w depth_mm(30, 40);
        for (auto& d : depth_mm) d = static_cast<std::uint16_t>(rng() % 8000);  // 0 = no reading
        writer.write(depth_mm);
    }
    writer.finish();
}

void expectSameDepth(const fs::path& a, const fs::path& b) {
    auto x = openDepthSource(a.string());
    auto y = openDepthSource(b.string());
    int frames = 0;
    while (auto fx = x->next()) {
        auto fy = y->next();
        ASSERT_TRUE(fy) << b << " ends after " << frames << " frames";
        EXPECT_EQ(cv::norm(fx->depth_mm, fy->depth_mm, cv::NORM_INF), 0.0) << "frame " << frames;
        ++frames;
    }
    EXPECT_FALSE(y->next());
    EXPECT_GT(frames, 0);
}

}  // namespace

TEST(ConvertCli, RecordingToOniAndBackIsBitIdentical) {
    const fs::path dir = freshTempDir("convert_roundtrip");
    writeRecording(dir / "rec", 4);
    const auto toOni =
        runMeadow("convert " + (dir / "rec").string() + " " + (dir / "rec.oni").string());
    ASSERT_EQ(toOni.exitCode, 0) << toOni.output;
    EXPECT_TRUE(fs::is_regular_file(dir / "rec.oni"));
    const auto back =
        runMeadow("convert " + (dir / "rec.oni").string() + " " + (dir / "back").string());
    ASSERT_EQ(back.exitCode, 0) << back.output;
    expectSameDepth(dir / "rec", dir / "back");
    for (const auto& entry : fs::directory_iterator(dir))  // outputs are renamed into place
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    fs::remove_all(dir);
}

TEST(ConvertCli, RealOniBecomesARecordingFolder) {
    if (!fs::exists(kRealOni)) GTEST_SKIP() << "shared data absent: " << kRealOni;
    const fs::path dir = freshTempDir("convert_real");
    const auto result = runMeadow("convert " + kRealOni.string() + " " + (dir / "room").string());
    ASSERT_EQ(result.exitCode, 0) << result.output;
    const RecordingInfo info = readRecordingInfo(dir / "room");
    EXPECT_EQ(info.frameCount, 12);
    EXPECT_EQ(info.intrinsics.width_px, 640);
    EXPECT_NEAR(info.intrinsics.fx_px, 575.8f, 0.1f);
    fs::remove_all(dir);
}

TEST(ConvertCli, CorruptOniIsOneLineAndNoOutput) {
    const fs::path dir = freshTempDir("convert_corrupt");
    {
        std::ofstream out(dir / "noise.oni", std::ios::binary);
        std::mt19937 rng(3);
        for (int i = 0; i < 50000; ++i) out.put(static_cast<char>(rng()));
    }
    const auto result =
        runMeadow("convert " + (dir / "noise.oni").string() + " " + (dir / "out").string());
    EXPECT_EQ(result.exitCode, 2) << result.output;
    EXPECT_EQ(countLines(result.output), 1) << result.output;
    EXPECT_EQ(result.output.rfind("meadow: ", 0), 0u) << result.output;
    EXPECT_NE(result.output.find("noise.oni"), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
    fs::remove_all(dir);
}

TEST(ConvertCli, TruncatedOniIsOneLine) {
    if (!fs::exists(kRealOni)) GTEST_SKIP() << "shared data absent: " << kRealOni;
    const fs::path dir = freshTempDir("convert_truncated");
    {
        std::ifstream in(kRealOni, std::ios::binary);
        std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        std::ofstream out(dir / "half.oni", std::ios::binary);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
    }
    const auto result =
        runMeadow("convert " + (dir / "half.oni").string() + " " + (dir / "out").string());
    EXPECT_EQ(result.exitCode, 2) << result.output;
    EXPECT_EQ(countLines(result.output), 1) << result.output;
    EXPECT_FALSE(fs::exists(dir / "out"));
    fs::remove_all(dir);
}

TEST(ConvertCli, NeedsExactlyOneOniSide) {
    const auto result = runMeadow("convert a_folder another_folder");
    EXPECT_EQ(result.exitCode, 2) << result.output;
    EXPECT_NE(result.output.find("RECORDING OUT.oni"), std::string::npos) << result.output;
}
