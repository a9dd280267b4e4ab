// `meadow render` as a user runs it: the real binary on the sample scene, the files it writes,
// exit codes and one-line messages for a missing or malformed scene and a missing library.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "cli_test_util.h"

namespace fs = std::filesystem;
using meadow::test::countLines;
using meadow::test::freshTempDir;
using meadow::test::runMeadow;

namespace {

const fs::path kSampleScene = fs::path(MEADOW_SOURCE_DIR) / "samples/scenes/meadow.json";

std::string readText(const fs::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(RenderCliTest, RendersTheSampleSceneToAPngAndStatsCsv) {
    const fs::path out = freshTempDir("render_sample") / "frames";
    const auto r = runMeadow("render " + kSampleScene.string() + " --out " + out.string() +
                             " --frames 1 --size 160x90");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const cv::Mat image = cv::imread((out / "frame_00000.png").string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(image.empty()) << r.output;
    EXPECT_EQ(image.cols, 160);
    EXPECT_EQ(image.rows, 90);
    EXPECT_FALSE(fs::exists(out / "frame_00001.png"));
    const std::string csv = readText(out / "stats.csv");
    EXPECT_EQ(countLines(csv), 2) << csv;  // header + one frame
    const std::string header = csv.substr(0, csv.find('\n'));
    for (const char* column : {"frame", "blades_total", "blades_drawn", "culled_orientation",
                               "culled_frustum", "culled_distance", "culled_occlusion", "frame_ms"})
        EXPECT_NE(header.find(column), std::string::npos) << "no " << column << " in " << header;
    EXPECT_NE(r.output.find("wrote 1 frame(s)"), std::string::npos) << r.output;
}

TEST(RenderCliTest, MissingSceneFileIsOneLineNamingItAndExitCode2) {
    const fs::path dir = freshTempDir("render_missing");
    const fs::path scene = dir / "no_such_scene.json";
    const auto r = runMeadow("render " + scene.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(countLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("no_such_scene.json"), std::string::npos) << r.output;
}

TEST(RenderCliTest, MalformedSceneIsOneLineNamingItAndExitCode2) {
    const fs::path dir = freshTempDir("render_malformed");
    const fs::path scene = dir / "broken_scene.json";
    std::ofstream(scene) << "{\"format\": \"meadow.scene\", \"version\": 1, \"grass\": [";
    const auto r = runMeadow("render " + scene.string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(countLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("broken_scene.json"), std::string::npos) << r.output;
}

TEST(RenderCliTest, MissingLibraryFileIsOneLineNamingItAndExitCode2) {
    const fs::path dir = freshTempDir("render_no_library");
    const fs::path library = dir / "no_such_library.json";
    const auto r = runMeadow("render " + kSampleScene.string() + " --out " +
                             (dir / "out").string() + " --library " + library.string());
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(countLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("no_such_library.json"), std::string::npos) << r.output;
}

TEST(RenderCliTest, HelpListsTheOptions) {
    const auto r = runMeadow("render --help");
    EXPECT_EQ(r.exitCode, 0) << r.output;
    for (const char* option : {"--out", "--frames", "--size", "--library"})
        EXPECT_NE(r.output.find(option), std::string::npos) << option << " missing:\n" << r.output;
}

}  // namespace
