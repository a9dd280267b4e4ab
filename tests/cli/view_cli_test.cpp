// `meadow view` as a user runs it: a scripted run in a virtual X display (Xvfb) writes a
// screenshot of grass under the scene's sky; without a display it says so in one line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "cli_test_util.h"

namespace fs = std::filesystem;
using meadow::test::countLines;
using meadow::test::freshTempDir;
using meadow::test::runCommand;
using meadow::test::runMeadow;

namespace {

const fs::path kSampleScene = fs::path(MEADOW_SOURCE_DIR) / "samples/scenes/meadow.json";
constexpr int kWidth_px = 320, kHeight_px = 180;

bool haveXvfbRun() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

// `meadow ARGS` in a fresh virtual X display of its own (-a: the first free display number).
// Under AddressSanitizer the windowed process runs without leak detection: glfwTerminate
// unloads the X11 libraries GLFW loaded, and what they kept for the process's lifetime is then
// reported as leaked from code no longer mapped (attributed to whatever library lies there
// now), which no suppression can name. The renderer's passes the window shares are checked for
// leaks headless (render_view_GLTest).
meadow::test::CommandResult runMeadowInXvfb(const std::string& args) {
    return runCommand(
        "ASAN_OPTIONS=\"${ASAN_OPTIONS}:detect_leaks=0\" xvfb-run -a -s '-screen 0 "
        "1280x1024x24' " +
        std::string(MEADOW_EXE) + " " + args);
}

cv::Vec3b sceneSkyBgr() {
    std::ifstream in(kSampleScene);
    const auto sky = nlohmann::json::parse(in).at("light").at("sky_color");
    auto channel = [](double v) { return static_cast<unsigned char>(std::lround(v * 255.0)); };
    return {channel(sky[2]), channel(sky[1]), channel(sky[0])};
}

double shareOfGreenDominantPixels(const cv::Mat& bgr) {
    int green = 0;
    for (int y = 0; y < bgr.rows; ++y)
        for (int x = 0; x < bgr.cols; ++x) {
            const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
            green += p[1] > p[2] && p[1] > p[0];
        }
    return static_cast<double>(green) / static_cast<double>(bgr.total());
}

// Share of the pixels of the top `rows` rows within `tolerance` of `color` in every channel.
double shareOfColorInTopRows(const cv::Mat& bgr, int rows, cv::Vec3b color, int tolerance) {
    int hits = 0;
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < bgr.cols; ++x) {
            const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
            bool near = true;
            for (int c = 0; c < 3; ++c) near = near && std::abs(p[c] - color[c]) <= tolerance;
            hits += near;
        }
    return static_cast<double>(hits) / (rows * bgr.cols);
}

TEST(ViewCli, ScriptedRunInXvfbWritesAScreenshotOfGrassUnderTheSky) {
    if (!haveXvfbRun())
        GTEST_SKIP() << "xvfb-run is not installed (Debian: apt-get install xvfb xauth)";
    const fs::path shot = freshTempDir("view_xvfb") / "shot.png";
    const auto r = runMeadowInXvfb("view " + kSampleScene.string() + " --size " +
                                   std::to_string(kWidth_px) + "x" + std::to_string(kHeight_px) +
                                   " --frames 20 --fixed-step --screenshot " + shot.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const cv::Mat image = cv::imread(shot.string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(image.empty()) << r.output;
    EXPECT_EQ(image.cols, kWidth_px);
    EXPECT_EQ(image.rows, kHeight_px);
    EXPECT_GT(shareOfGreenDominantPixels(image), 0.10) << "too little grass in " << shot;
    const cv::Vec3b sky = sceneSkyBgr();
    EXPECT_GT(shareOfColorInTopRows(image, 4, sky, 2), 0.5)
        << "the sky " << sky << " is missing from the top rows of " << shot;
    EXPECT_NE(r.output.find("viewed 20 frame(s)"), std::string::npos) << r.output;
}

TEST(ViewCli, WithoutADisplayExitsTwoWithOneLineOnStderrNamingIt) {
    // stderr alone reaches the pipe; stdout is discarded.
    const auto r = runCommand("{ env -u DISPLAY -u WAYLAND_DISPLAY " + std::string(MEADOW_EXE) +
                              " view " + kSampleScene.string() + " 2>&1 >/dev/null; }");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(countLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("no display"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("DISPLAY"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("meadow render"), std::string::npos) << r.output;
}

TEST(ViewCli, ScreenshotWithoutFramesIsAUsageError) {
    const auto r = runMeadow("view " + kSampleScene.string() + " --screenshot x.png");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(countLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("--frames"), std::string::npos) << r.output;
}

TEST(ViewCli, HelpListsTheOptionsAndTheKeys) {
    const auto r = runMeadow("view --help");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    for (const char* text :
         {"--library", "--size", "--frames", "--screenshot", "--fixed-step", "WASD", "F12", "Esc"})
        EXPECT_NE(r.output.find(text), std::string::npos) << text << " missing:\n" << r.output;
}

}  // namespace
