// `meadow render --video`: the frames as an MP4 (through ffmpeg, which the README's set-up
// installs), checked with ffprobe; without ffmpeg, one line that says what to install.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "cli_test_util.h"

namespace fs = std::filesystem;
using meadow::test::countLines;
using meadow::test::freshTempDir;
using meadow::test::runCommand;
using meadow::test::runMeadow;

namespace {

const fs::path kSampleScene = fs::path(MEADOW_SOURCE_DIR) / "samples/scenes/meadow.json";

struct Probe {
    int frames = 0, width = 0, height = 0;
    std::string codec;
};

// ffprobe's count of decoded frames, size and codec of the video's first stream.
Probe probe(const fs::path& video) {
    const auto r = runCommand(
        "ffprobe -v error -count_frames -select_streams v:0 -show_entries "
        "stream=nb_read_frames,width,height,codec_name -of default=noprint_wrappers=1 " +
        video.string());
    Probe p;
    std::istringstream lines(r.output);
    std::string line;
    while (std::getline(lines, line)) {
        const auto eq = line.find('=');
        if (eq == std::string::npos) continue;
        const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
        if (key == "nb_read_frames") p.frames = std::stoi(value);
        if (key == "width") p.width = std::stoi(value);
        if (key == "height") p.height = std::stoi(value);
        if (key == "codec_name") p.codec = value;
    }
    return p;
}

TEST(RenderVideoTest, WritesEveryFrameAsAnH264Mp4AndNothingElse) {
    ASSERT_EQ(runCommand("command -v ffprobe").exitCode, 0)
        << "ffmpeg is part of meadow's set-up (./meadow.sh deps)";
    const fs::path dir = freshTempDir("render_video");
    const fs::path video = dir / "meadow.mp4";
    const auto r = runMeadow("render " + kSampleScene.string() + " --video " + video.string() +
                             " --frames 12 --size 160x90");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Probe p = probe(video);
    EXPECT_EQ(p.frames, 12);
    EXPECT_EQ(p.width, 160);
    EXPECT_EQ(p.height, 90);
    EXPECT_EQ(p.codec, "h264");
    EXPECT_NE(r.output.find(video.string()), std::string::npos) << "says where: " << r.output;
    int files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
    EXPECT_EQ(files, 1) << "no temporaries or logs left beside the video";
}

TEST(RenderVideoTest, OddSizesArePaddedToWhatH264Needs) {
    ASSERT_EQ(runCommand("command -v ffprobe").exitCode, 0);
    const fs::path video = freshTempDir("render_video_odd") / "odd.mp4";
    const auto r = runMeadow("render " + kSampleScene.string() + " --video " + video.string() +
                             " --frames 2 --size 81x45");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const Probe p = probe(video);
    EXPECT_EQ(p.frames, 2);
    EXPECT_EQ(p.width, 82);
    EXPECT_EQ(p.height, 46);
}

TEST(RenderVideoTest, WithoutFfmpegItIsOneLineSayingWhatToInstallAndWritesNothing) {
    const fs::path dir = freshTempDir("render_video_no_ffmpeg");
    const auto r = runCommand("PATH=/nonexistent " + std::string(MEADOW_EXE) + " render " +
                              kSampleScene.string() + " --video " + (dir / "v.mp4").string() +
                              " --frames 2 --size 80x45");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(countLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("apt-get install ffmpeg"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::is_empty(dir)) << "nothing written";
}

TEST(RenderVideoTest, NeitherFramesNorVideoIsAUsageError) {
    const auto r = runMeadow("render " + kSampleScene.string() + " --frames 2");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(countLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("--out"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--video"), std::string::npos) << r.output;
}

}  // namespace
