// Recordings: write-then-read round trips, the writer's promises (atomic files, overwrite only
// a recording), plain PNG folders in other depth units, and one real TUM RGB-D frame.
#include "meadow/capture/recording.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>

#include "meadow/capture/depth_source.h"
#include "meadow/capture/error.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
using namespace meadow::capture;

namespace {

fs::path freshDir(const std::string& name) {
    return meadow::test::freshTempDir("recording_" + name);
}

RecordingInfo smallInfo() {
    RecordingInfo info;
    info.sensor = "test-sensor";
    info.intrinsics = {.width_px = 32,
                       .height_px = 24,
                       .fx_px = 28.79f,
                       .fy_px = 28.81f,
                       .cx_px = 15.5f,
                       .cy_px = 11.25f};
    info.frameRate_hz = 15.0;
    return info;
}

// Random depth over the whole 16-bit range, with holes (0) and the extremes present.
cv::Mat1w randomDepth_mm(const Intrinsics& k, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> value(0, 65535);
    cv::Mat1w depth(k.height_px, k.width_px);
    for (auto& d : depth) d = static_cast<std::uint16_t>(value(rng));
    depth(0, 0) = 0;
    depth(0, 1) = 65535;
    depth(1, 0) = 0;
    return depth;
}

bool identical(const cv::Mat1w& a, const cv::Mat1w& b) {
    return a.size() == b.size() && cv::countNonZero(a != b) == 0;
}

std::vector<fs::path> filesUnder(const fs::path& dir) {
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        if (e.is_regular_file()) files.push_back(e.path());
    return files;
}

bool anyTemporaryUnder(const fs::path& dir) {
    for (const auto& file : filesUnder(dir))
        if (file.filename().string().find(".tmp.") != std::string::npos) return true;
    return false;
}

void writeRecording(const fs::path& folder, const RecordingInfo& info,
                    const std::vector<cv::Mat1w>& frames) {
    RecordingWriter writer(folder, info);
    for (const auto& f : frames) writer.write(f);
    writer.finish();
}

std::vector<DepthFrame> readAll(DepthSource& source) {
    std::vector<DepthFrame> frames;
    while (auto frame = source.next()) frames.push_back(std::move(*frame));
    return frames;
}

// --intrinsics for a plain folder: TUM RGB-D's camera for its 640 x 480 frames, and a camera of
// the same field of view for the tests' tiny frames (a 525 px focal length across 2 px is no
// camera's).
SourceOptions plainOptions(DepthUnit unit, int width_px = 640, int height_px = 480) {
    const float f_px = 525.f * static_cast<float>(width_px) / 640.f;
    Intrinsics k;
    k.fx_px = k.fy_px = f_px;
    k.cx_px = 0.5f * static_cast<float>(width_px - 1);
    k.cy_px = 0.5f * static_cast<float>(height_px - 1);
    k.width_px = k.height_px = 0;  // as parseIntrinsics leaves them: the first frame's
    return {.intrinsics = k, .depthUnit = unit};
}

}  // namespace

TEST(RecordingRoundTrip, WriteThenReadIsBitIdentical) {
    const fs::path folder = freshDir("roundtrip");
    const RecordingInfo info = smallInfo();
    const std::vector<cv::Mat1w> written = {randomDepth_mm(info.intrinsics, 1),
                                            randomDepth_mm(info.intrinsics, 2),
                                            cv::Mat1w::zeros(24, 32)};
    writeRecording(folder, info, written);

    const auto source = openDepthSource(folder.string());
    EXPECT_EQ(source->info().sensor, "test-sensor");
    EXPECT_EQ(source->info().intrinsics, info.intrinsics);
    EXPECT_EQ(source->info().depthUnit, DepthUnit::Millimetre);
    EXPECT_EQ(source->info().frameCount, 3);
    EXPECT_EQ(source->info().frameRate_hz, 15.0);
    const std::vector<DepthFrame> read = readAll(*source);
    ASSERT_EQ(read.size(), written.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
        EXPECT_TRUE(identical(read[i].depth_mm, written[i])) << "frame " << i;
        EXPECT_EQ(read[i].index, static_cast<int>(i));
        EXPECT_DOUBLE_EQ(read[i].timestamp_s, static_cast<double>(i) / 15.0) << "frame " << i;
        EXPECT_EQ(read[i].intrinsics, info.intrinsics);
    }
    EXPECT_FALSE(source->next().has_value()) << "the end stays the end";
}

TEST(RecordingRoundTrip, ReadRecordingInfoReturnsWhatWasWritten) {
    const fs::path folder = freshDir("info");
    RecordingInfo info = smallInfo();
    info.intrinsics.fx_px = 575.8f;  // not exact in binary: must still round trip bit for bit
    writeRecording(folder, info, {randomDepth_mm(info.intrinsics, 3)});
    const RecordingInfo read = readRecordingInfo(folder);
    EXPECT_EQ(read.sensor, info.sensor);
    EXPECT_EQ(read.intrinsics, info.intrinsics);
    EXPECT_EQ(read.frameCount, 1);
    EXPECT_EQ(read.frameRate_hz, info.frameRate_hz);
}

TEST(RecordingWriter, RecordingJsonHoldsFormatVersionAndEveryField) {
    const fs::path folder = freshDir("json");
    const RecordingInfo info = smallInfo();
    writeRecording(folder, info,
                   {randomDepth_mm(info.intrinsics, 4), randomDepth_mm(info.intrinsics, 5)});
    std::ifstream in(folder / "recording.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("format"), "meadow.recording");
    EXPECT_EQ(j.at("version"), 1);
    EXPECT_EQ(j.at("sensor"), "test-sensor");
    EXPECT_EQ(j.at("width_px"), 32);
    EXPECT_EQ(j.at("height_px"), 24);
    EXPECT_EQ(j.at("fx_px"), 28.79);  // shortest decimal of the float, not 28.7900009...
    EXPECT_EQ(j.at("cy_px"), 11.25);
    EXPECT_EQ(j.at("depth_unit"), "mm");
    EXPECT_EQ(j.at("frame_count"), 2);
    EXPECT_EQ(j.at("frame_rate_hz"), 15.0);
    EXPECT_TRUE(fs::is_regular_file(folder / "depth" / "000000.png"));
    EXPECT_TRUE(fs::is_regular_file(folder / "depth" / "000001.png"));
    EXPECT_EQ(filesUnder(folder).size(), 3u) << "recording.json and two frames, nothing else";
}

TEST(RecordingWriter, StoresMillimetresWhateverTheInfoUnitSays) {
    const fs::path folder = freshDir("unit");
    RecordingInfo info = smallInfo();
    info.depthUnit = DepthUnit::FifthMillimetre;  // e.g. copied from a TUM source
    const cv::Mat1w frame = randomDepth_mm(info.intrinsics, 6);
    writeRecording(folder, info, {frame});
    const auto source = openDepthSource(folder.string());
    EXPECT_EQ(source->info().depthUnit, DepthUnit::Millimetre);
    EXPECT_TRUE(identical(source->next()->depth_mm, frame));
}

TEST(RecordingWriter, OverwritingARecordingReplacesItWhole) {
    const fs::path folder = freshDir("overwrite");
    const RecordingInfo info = smallInfo();
    writeRecording(folder, info,
                   {randomDepth_mm(info.intrinsics, 7), randomDepth_mm(info.intrinsics, 8),
                    randomDepth_mm(info.intrinsics, 9)});
    const cv::Mat1w only = randomDepth_mm(info.intrinsics, 10);
    writeRecording(folder, info, {only});
    EXPECT_EQ(filesUnder(folder).size(), 2u) << "old frames 1 and 2 must be gone";
    const auto source = openDepthSource(folder.string());
    const std::vector<DepthFrame> read = readAll(*source);
    ASSERT_EQ(read.size(), 1u);
    EXPECT_TRUE(identical(read[0].depth_mm, only));
}

TEST(RecordingWriter, OverwritingAnUnfinishedRecordingIsAllowed) {
    const fs::path folder = freshDir("unfinished_overwrite");
    const RecordingInfo info = smallInfo();
    {
        RecordingWriter writer(folder, info);
        writer.write(randomDepth_mm(info.intrinsics, 11));
        // no finish(): as if the capture crashed
    }
    EXPECT_FALSE(fs::exists(folder / "recording.json"));
    writeRecording(folder, info, {randomDepth_mm(info.intrinsics, 12)});
    EXPECT_EQ(readRecordingInfo(folder).frameCount, 1);
}

TEST(RecordingWriter, RefusesToOverwriteAFolderThatIsNotARecording) {
    const fs::path folder = freshDir("not_a_recording");
    std::ofstream(folder / "notes.txt") << "precious";
    try {
        RecordingWriter writer(folder, smallInfo());
        FAIL() << "overwrote a folder that is not a recording";
    } catch (const CaptureError& e) {
        EXPECT_NE(std::string(e.what()).find(folder.string()), std::string::npos) << e.what();
    }
    EXPECT_TRUE(fs::exists(folder / "notes.txt"));
    EXPECT_FALSE(fs::exists(folder / "depth"));
}

TEST(RecordingWriter, RefusesToOverwriteAForeignRecordingJson) {
    const fs::path folder = freshDir("foreign_json");
    std::ofstream(folder / "recording.json") << R"({"format": "someone.else", "version": 1})";
    EXPECT_THROW(RecordingWriter(folder, smallInfo()), CaptureError);
    EXPECT_TRUE(fs::exists(folder / "recording.json"));
}

TEST(RecordingWriter, FailedFrameWriteLeavesNoHalfFile) {
    const fs::path folder = freshDir("failed_frame");
    const RecordingInfo info = smallInfo();
    RecordingWriter writer(folder, info);
    writer.write(randomDepth_mm(info.intrinsics, 13));
    // A non-empty folder where frame 1 must go: the rename onto it fails.
    fs::create_directories(folder / "depth" / "000001.png");
    std::ofstream(folder / "depth" / "000001.png" / "blocker") << "x";
    try {
        writer.write(randomDepth_mm(info.intrinsics, 14));
        FAIL() << "the write should have failed";
    } catch (const CaptureError& e) {
        EXPECT_NE(std::string(e.what()).find("000001.png"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(anyTemporaryUnder(folder)) << "the temporary must be removed";
    EXPECT_EQ(writer.framesWritten(), 1);
    EXPECT_EQ(filesUnder(folder / "depth").size(), 2u) << "frame 0 and the blocker only";
    EXPECT_TRUE(fs::is_directory(folder / "depth" / "000001.png"));
}

TEST(RecordingWriter, FailedFinishLeavesNoRecordingJson) {
    const fs::path folder = freshDir("failed_finish");
    const RecordingInfo info = smallInfo();
    RecordingWriter writer(folder, info);
    writer.write(randomDepth_mm(info.intrinsics, 15));
    fs::create_directories(folder / "recording.json" / "blocker");
    EXPECT_THROW(writer.finish(), CaptureError);
    EXPECT_FALSE(anyTemporaryUnder(folder));
    EXPECT_FALSE(fs::is_regular_file(folder / "recording.json"));
}

TEST(RecordingWriter, UnwritableFolderIsACaptureError) {
    EXPECT_THROW(RecordingWriter("/proc/meadow_cannot_write_here/rec", smallInfo()), CaptureError);
}

TEST(RecordingWriter, BrokenPreconditionsAreProgrammerErrors) {
    const fs::path folder = freshDir("preconditions");
    RecordingInfo badIntrinsics = smallInfo();
    badIntrinsics.intrinsics.fx_px = std::numeric_limits<float>::quiet_NaN();
    EXPECT_THROW(RecordingWriter(folder, badIntrinsics), std::invalid_argument);
    RecordingInfo badRate = smallInfo();
    badRate.frameRate_hz = 0.0;
    EXPECT_THROW(RecordingWriter(folder, badRate), std::invalid_argument);

    RecordingWriter writer(folder, smallInfo());
    EXPECT_THROW(writer.finish(), std::logic_error) << "no frame yet";
    EXPECT_THROW(writer.write(cv::Mat1w::zeros(10, 10)), std::invalid_argument);
    EXPECT_THROW(writer.write(cv::Mat1w()), std::invalid_argument);
    writer.write(cv::Mat1w::zeros(24, 32));
    writer.finish();
    EXPECT_THROW(writer.write(cv::Mat1w::zeros(24, 32)), std::logic_error);
    EXPECT_THROW(writer.finish(), std::logic_error);
}

TEST(RecordingWriter, MovedWriterKeepsWriting) {
    const fs::path folder = freshDir("moved");
    const RecordingInfo info = smallInfo();
    RecordingWriter first(folder, info);
    first.write(randomDepth_mm(info.intrinsics, 16));
    RecordingWriter second = std::move(first);
    second.write(randomDepth_mm(info.intrinsics, 17));
    second.finish();
    EXPECT_EQ(readRecordingInfo(folder).frameCount, 2);
}

TEST(RecordingPlainFolder, FifthMillimetreUnitsAreConvertedToMillimetres) {
    const fs::path folder = freshDir("fifth_mm");
    // Stored 0.2 mm steps -> expected millimetres, rounded to nearest (v/5 never ties).
    const std::vector<std::pair<std::uint16_t, std::uint16_t>> cases = {
        {0, 0}, {5, 1}, {7, 1}, {8, 2}, {5000, 1000}, {7509, 1502}, {46500, 9300}, {65535, 13107}};
    cv::Mat1w stored(1, static_cast<int>(cases.size()));
    for (std::size_t i = 0; i < cases.size(); ++i) stored(0, static_cast<int>(i)) = cases[i].first;
    ASSERT_TRUE(cv::imwrite((folder / "frame.png").string(), stored));

    const SourceOptions options =
        plainOptions(DepthUnit::FifthMillimetre, static_cast<int>(cases.size()), 1);
    const auto source = openDepthSource(folder.string(), options);
    EXPECT_EQ(source->info().intrinsics.width_px, static_cast<int>(cases.size()))
        << "width comes from the first frame";
    EXPECT_EQ(source->info().intrinsics.height_px, 1);
    EXPECT_EQ(source->info().intrinsics.fx_px, options.intrinsics->fx_px);
    const auto frame = source->next();
    ASSERT_TRUE(frame.has_value());
    for (std::size_t i = 0; i < cases.size(); ++i)
        EXPECT_EQ(frame->depth_mm(0, static_cast<int>(i)), cases[i].second)
            << "stored " << cases[i].first << " x 0.2 mm";
    EXPECT_FALSE(source->next().has_value());
}

TEST(RecordingPlainFolder, MetreUnitsAreConvertedAndOutOfRangeBecomesNoReading) {
    const fs::path folder = freshDir("metre");
    cv::Mat1w stored = (cv::Mat1w(1, 5) << 0, 1, 2, 65, 66);
    ASSERT_TRUE(cv::imwrite((folder / "a.png").string(), stored));
    const auto source = openDepthSource(folder.string(), plainOptions(DepthUnit::Metre, 5, 1));
    const cv::Mat1w expected = (cv::Mat1w(1, 5) << 0, 1000, 2000, 65000, 0);
    EXPECT_TRUE(identical(source->next()->depth_mm, expected));
}

TEST(RecordingPlainFolder, FramesComeInNameOrderAndOtherFilesAreIgnored) {
    const fs::path folder = freshDir("order");
    for (int value : {3, 1, 2})
        ASSERT_TRUE(cv::imwrite((folder / ("frame_" + std::to_string(value) + ".png")).string(),
                                cv::Mat1w(2, 2, static_cast<std::uint16_t>(value))));
    std::ofstream(folder / "notes.txt") << "not a frame";
    const auto source = openDepthSource(folder.string(), plainOptions(DepthUnit::Millimetre, 2, 2));
    EXPECT_EQ(source->info().frameCount, 3);
    const std::vector<DepthFrame> frames = readAll(*source);
    ASSERT_EQ(frames.size(), 3u);
    for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(frames[static_cast<std::size_t>(i)].depth_mm(0, 0), i + 1);
        EXPECT_EQ(frames[static_cast<std::size_t>(i)].index, i);
        EXPECT_DOUBLE_EQ(frames[static_cast<std::size_t>(i)].timestamp_s,
                         i / source->info().frameRate_hz);
    }
}

TEST(RecordingParseIntrinsics, ReadsFourNumbersInPixels) {
    const Intrinsics k = parseIntrinsics("525, 526,319.5 ,239.5");
    EXPECT_EQ(k.fx_px, 525.f);
    EXPECT_EQ(k.fy_px, 526.f);
    EXPECT_EQ(k.cx_px, 319.5f);
    EXPECT_EQ(k.cy_px, 239.5f);
    EXPECT_EQ(k.width_px, 0) << "the size is the first frame's";
    EXPECT_EQ(k.height_px, 0);
}

TEST(RecordingParseIntrinsics, MalformedTextIsACaptureErrorShowingTheExpectedForm) {
    for (const std::string text : {"", "525,525,319.5", "525,525,319.5,239.5,1", "a,b,c,d",
                                   "525,,319.5,239.5", "525x,525,319.5,239.5", "nan,525,1,1",
                                   "inf,525,1,1", "525,-525,1,1", "0,525,1,1", "1e50,525,1,1"}) {
        try {
            (void)parseIntrinsics(text);
            ADD_FAILURE() << "accepted \"" << text << "\"";
        } catch (const CaptureError& e) {
            EXPECT_NE(std::string(e.what()).find("--intrinsics"), std::string::npos) << e.what();
        }
    }
}

// One real Kinect v1 frame from the TUM RGB-D benchmark, stored in 0.2 mm units; its README
// (shared/data/real/tum-frame/README.txt) states: 640x480, valid ~1.5..9.3 m, ~19 % zeros.
TEST(RecordingPlainFolder, RealTumFrameReadsAsStatedInItsReadme) {
    const fs::path tum = fs::path(MEADOW_SHARED_DATA_DIR) / "real/tum-frame/TUM_depth.png";
    if (!fs::exists(tum)) GTEST_SKIP() << "real TUM frame not found at " << tum;
    const fs::path folder = freshDir("tum");
    fs::copy_file(tum, folder / "TUM_depth.png");

    const auto source = openDepthSource(folder.string(), plainOptions(DepthUnit::FifthMillimetre));
    EXPECT_EQ(source->info().frameCount, 1);
    EXPECT_EQ(source->info().intrinsics.width_px, 640);
    EXPECT_EQ(source->info().intrinsics.height_px, 480);
    const auto frame = source->next();
    ASSERT_TRUE(frame.has_value());
    const cv::Mat1w& depth_mm = frame->depth_mm;

    const double zeroFraction =
        1.0 - cv::countNonZero(depth_mm) / static_cast<double>(depth_mm.total());
    EXPECT_NEAR(zeroFraction, 0.19, 0.02);
    double min_mm = 0, max_mm = 0;
    cv::minMaxLoc(depth_mm, &min_mm, &max_mm, nullptr, nullptr, depth_mm > 0);
    EXPECT_NEAR(min_mm, 1500.0, 100.0) << "valid depth starts near 1.5 m";
    EXPECT_NEAR(max_mm, 9300.0, 200.0) << "valid depth ends near 9.3 m";

    // Read as millimetres it would be 5x too far: the unit really is 0.2 mm.
    const cv::Mat1w raw = cv::imread(tum.string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(raw.empty());
    cv::Mat1w expected_mm;
    raw.convertTo(expected_mm, CV_16U, 0.2);
    EXPECT_TRUE(identical(depth_mm, expected_mm));
}

TEST(RecordingNames, FrameFileNamesAreSixOrMoreDigitsDotPngOrTheirTemporary) {
    using meadow::capture::isFrameFileName;
    EXPECT_TRUE(isFrameFileName("000000.png"));
    EXPECT_TRUE(isFrameFileName("1234567.png"));
    EXPECT_TRUE(isFrameFileName("000003.png.tmp.991"));
    EXPECT_FALSE(isFrameFileName("00001.png"));
    EXPECT_FALSE(isFrameFileName("00000a.png"));
    EXPECT_FALSE(isFrameFileName("000001.jpg"));
    EXPECT_FALSE(isFrameFileName("readme"));
}
