// Bad recordings and bad plain folders: each gives one CaptureError that names the file and
// says what to do; none crashes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "meadow/capture/depth_source.h"
#include "meadow/capture/error.h"
#include "meadow/capture/recording.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
using namespace meadow::capture;

namespace {

fs::path freshDir(const std::string& name) {
    return meadow::test::freshTempDir("recording_errors_" + name);
}

RecordingInfo smallInfo() {
    RecordingInfo info;
    info.sensor = "test-sensor";
    info.intrinsics = {.width_px = 16,
                       .height_px = 12,
                       .fx_px = 14.f,
                       .fy_px = 14.f,
                       .cx_px = 7.5f,
                       .cy_px = 5.5f};
    return info;
}

cv::Mat1w rampDepth_mm(int width, int height) {
    cv::Mat1w depth(height, width);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            depth(y, x) = static_cast<std::uint16_t>(500 + 37 * x + 101 * y);
    return depth;
}

// A finished, valid recording of `frames` frames of smallInfo()'s size.
fs::path validRecording(const std::string& name, int frames = 2) {
    const fs::path folder = freshDir(name);
    RecordingWriter writer(folder, smallInfo());
    for (int i = 0; i < frames; ++i) writer.write(rampDepth_mm(16, 12));
    writer.finish();
    return folder;
}

SourceOptions plainOptions() {
    return {.intrinsics = parseIntrinsics("14,14,7.5,5.5"), .depthUnit = DepthUnit::Millimetre};
}

// Opens `uri` and reads every frame; returns the CaptureError's message, failing the test if
// nothing or anything else was thrown.
std::string errorReading(const std::string& uri, const SourceOptions& options = {}) {
    try {
        const auto source = openDepthSource(uri, options);
        while (source->next()) {
        }
    } catch (const CaptureError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        return message;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected CaptureError, got " << typeid(e).name() << ": " << e.what();
        return {};
    }
    ADD_FAILURE() << "reading " << uri << " should have failed";
    return {};
}

bool mentions(const std::string& message, const std::string& what) {
    return message.find(what) != std::string::npos;
}

std::string slurp(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void spit(const fs::path& file, const std::string& bytes) {
    std::ofstream(file, std::ios::binary | std::ios::trunc) << bytes;
}

// Rewrites recording.json after applying `edit` to its JSON.
void editJson(const fs::path& folder, const std::function<void(nlohmann::json&)>& edit) {
    nlohmann::json j = nlohmann::json::parse(slurp(folder / "recording.json"));
    edit(j);
    spit(folder / "recording.json", j.dump());
}

}  // namespace

// --- frames ----------------------------------------------------------------------------------

TEST(RecordingErrors, EightBitFrameNamesTheFileAndAsksFor16Bit) {
    const fs::path folder = validRecording("eight_bit");
    const fs::path bad = folder / "depth" / "000001.png";
    ASSERT_TRUE(cv::imwrite(bad.string(), cv::Mat1b(12, 16, 128)));
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, bad.string())) << message;
    EXPECT_TRUE(mentions(message, "8-bit")) << message;
    EXPECT_TRUE(mentions(message, "16-bit")) << message;
}

TEST(RecordingErrors, ColourFrameInAPlainFolderNamesTheFile) {
    const fs::path folder = freshDir("colour");
    const fs::path bad = folder / "a.png";
    ASSERT_TRUE(cv::imwrite(bad.string(), cv::Mat3b(12, 16, cv::Vec3b(10, 20, 30))));
    const std::string message = errorReading(folder.string(), plainOptions());
    EXPECT_TRUE(mentions(message, bad.string())) << message;
    EXPECT_TRUE(mentions(message, "colour")) << message;
}

TEST(RecordingErrors, SixteenBitColourFrameIsRejected) {
    const fs::path folder = freshDir("colour16");
    const fs::path bad = folder / "a.png";
    ASSERT_TRUE(
        cv::imwrite(bad.string(), cv::Mat_<cv::Vec3w>(12, 16, cv::Vec3w(1000, 2000, 3000))));
    const std::string message = errorReading(folder.string(), plainOptions());
    EXPECT_TRUE(mentions(message, bad.string())) << message;
    EXPECT_TRUE(mentions(message, "single-channel")) << message;
}

TEST(RecordingErrors, TruncatedFrameNamesTheFileAtEveryCut) {
    const fs::path folder = validRecording("truncated");
    const fs::path frame = folder / "depth" / "000001.png";
    const std::string whole = slurp(frame);
    ASSERT_GT(whole.size(), 60u);
    for (std::size_t keep : {std::size_t{4}, std::size_t{8}, std::size_t{20}, std::size_t{40},
                             whole.size() / 2, whole.size() - 13, whole.size() - 1}) {
        spit(frame, whole.substr(0, keep));
        const std::string message = errorReading(folder.string());
        EXPECT_TRUE(mentions(message, frame.string())) << "kept " << keep << ": " << message;
        EXPECT_TRUE(mentions(message, keep < 8 ? "not a PNG" : "truncated"))
            << "kept " << keep << ": " << message;
    }
}

TEST(RecordingErrors, CorruptFrameNamesTheFile) {
    const fs::path folder = validRecording("corrupt");
    const fs::path frame = folder / "depth" / "000000.png";
    std::string bytes = slurp(frame);
    for (std::size_t i = 40; i + 20 < bytes.size(); i += 7) bytes[i] = static_cast<char>(~bytes[i]);
    spit(frame, bytes);
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, frame.string())) << message;
    EXPECT_TRUE(mentions(message, "corrupt")) << message;
}

TEST(RecordingErrors, EmptyFrameFileNamesTheFile) {
    const fs::path folder = validRecording("empty_frame");
    const fs::path frame = folder / "depth" / "000001.png";
    spit(frame, "");
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, frame.string())) << message;
    EXPECT_TRUE(mentions(message, "empty")) << message;
}

TEST(RecordingErrors, FrameThatIsNotAPngNamesTheFile) {
    const fs::path folder = freshDir("not_png");
    spit(folder / "a.png", "this is text, not a picture");
    const std::string message = errorReading(folder.string(), plainOptions());
    EXPECT_TRUE(mentions(message, (folder / "a.png").string())) << message;
    EXPECT_TRUE(mentions(message, "not a PNG")) << message;
}

TEST(RecordingErrors, FrameOfAnotherSizeMidRecordingNamesTheFile) {
    const fs::path folder = validRecording("size", 3);
    const fs::path bad = folder / "depth" / "000002.png";
    ASSERT_TRUE(cv::imwrite(bad.string(), rampDepth_mm(20, 12)));
    const auto source = openDepthSource(folder.string());
    EXPECT_TRUE(source->next().has_value());
    EXPECT_TRUE(source->next().has_value());
    try {
        (void)source->next();
        FAIL() << "a 20x12 frame in a 16x12 recording was accepted";
    } catch (const CaptureError& e) {
        EXPECT_TRUE(mentions(e.what(), bad.string())) << e.what();
        EXPECT_TRUE(mentions(e.what(), "20x12")) << e.what();
        EXPECT_TRUE(mentions(e.what(), "16x12")) << e.what();
    }
}

TEST(RecordingErrors, FirstFrameOfAnotherSizeThanRecordingJsonNamesTheFile) {
    const fs::path folder = validRecording("first_size");
    const fs::path bad = folder / "depth" / "000000.png";
    ASSERT_TRUE(cv::imwrite(bad.string(), rampDepth_mm(16, 13)));
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, bad.string())) << message;
}

TEST(RecordingErrors, FrameOfAnotherSizeInAPlainFolderNamesTheFile) {
    const fs::path folder = freshDir("plain_size");
    ASSERT_TRUE(cv::imwrite((folder / "a.png").string(), rampDepth_mm(16, 12)));
    ASSERT_TRUE(cv::imwrite((folder / "b.png").string(), rampDepth_mm(8, 6)));
    const std::string message = errorReading(folder.string(), plainOptions());
    EXPECT_TRUE(mentions(message, (folder / "b.png").string())) << message;
    EXPECT_TRUE(mentions(message, "a.png")) << "says where the size came from: " << message;
}

TEST(RecordingErrors, MissingFrameNamesTheFile) {
    const fs::path folder = validRecording("missing_frame", 3);
    fs::remove(folder / "depth" / "000001.png");
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, (folder / "depth" / "000001.png").string())) << message;
}

TEST(RecordingErrors, HugeFrameCountNamesTheFirstMissingFrame) {
    const fs::path folder = validRecording("huge_count");
    editJson(folder, [](nlohmann::json& j) { j["frame_count"] = 2147483647; });
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, (folder / "depth" / "000002.png").string())) << message;
}

// --- folders ---------------------------------------------------------------------------------

TEST(RecordingErrors, PlainFolderWithoutOptionsAsksForIntrinsicsAndDepthUnit) {
    const fs::path folder = freshDir("no_options");
    ASSERT_TRUE(cv::imwrite((folder / "a.png").string(), rampDepth_mm(16, 12)));
    SourceOptions onlyIntrinsics, onlyUnit;
    onlyIntrinsics.intrinsics = parseIntrinsics("1,1,1,1");
    onlyUnit.depthUnit = DepthUnit::Millimetre;
    for (const SourceOptions& options : {SourceOptions{}, onlyIntrinsics, onlyUnit}) {
        const std::string message = errorReading(folder.string(), options);
        EXPECT_TRUE(mentions(message, (folder / "recording.json").string())) << message;
        EXPECT_TRUE(mentions(message, "--intrinsics")) << message;
        EXPECT_TRUE(mentions(message, "--depth-unit")) << message;
    }
}

TEST(RecordingErrors, UnfinishedRecordingSaysSo) {
    const fs::path folder = freshDir("unfinished");
    {
        RecordingWriter writer(folder, smallInfo());
        writer.write(rampDepth_mm(16, 12));
    }
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, (folder / "recording.json").string())) << message;
    EXPECT_TRUE(mentions(message, "not finished")) << message;
}

TEST(RecordingErrors, MissingFolderNamesIt) {
    const fs::path folder = freshDir("missing") / "nowhere";
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, folder.string())) << message;
    EXPECT_TRUE(mentions(message, "does not exist")) << message;
    EXPECT_THROW(readRecordingInfo(folder), CaptureError);
}

TEST(RecordingErrors, EmptyFolderNamesIt) {
    const fs::path folder = freshDir("empty");
    const std::string message = errorReading(folder.string(), plainOptions());
    EXPECT_TRUE(mentions(message, folder.string())) << message;
    EXPECT_TRUE(mentions(message, "no .png")) << message;
}

TEST(RecordingErrors, SingleFileInsteadOfAFolderNamesIt) {
    const fs::path folder = freshDir("single_file");
    ASSERT_TRUE(cv::imwrite((folder / "a.png").string(), rampDepth_mm(16, 12)));
    const std::string message = errorReading((folder / "a.png").string(), plainOptions());
    EXPECT_TRUE(mentions(message, (folder / "a.png").string())) << message;
}

TEST(RecordingErrors, EmptyUriSaysWhatToGive) {
    EXPECT_TRUE(mentions(errorReading(""), "recording folder"));
}

// --- recording.json --------------------------------------------------------------------------

TEST(RecordingErrors, MalformedJsonNamesTheFile) {
    const fs::path folder = validRecording("malformed");
    const std::string text = slurp(folder / "recording.json");
    for (const std::string& bad : {text.substr(0, text.size() / 2), std::string(""),
                                   std::string("{\"format\": \"meadow.recording\",}"),
                                   std::string("[1, 2, 3]"), std::string("\"meadow.recording\"")}) {
        spit(folder / "recording.json", bad);
        const std::string message = errorReading(folder.string());
        EXPECT_TRUE(mentions(message, (folder / "recording.json").string()))
            << "text " << bad << ": " << message;
    }
}

TEST(RecordingErrors, UnknownFormatNameNamesTheFile) {
    const fs::path folder = validRecording("format");
    editJson(folder, [](nlohmann::json& j) { j["format"] = "meadow.library"; });
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, (folder / "recording.json").string())) << message;
    EXPECT_TRUE(mentions(message, "meadow.library")) << message;
    EXPECT_TRUE(mentions(message, "not a meadow recording")) << message;
}

TEST(RecordingErrors, UnknownVersionNamesTheFileAndTheVersions) {
    const fs::path folder = validRecording("version");
    editJson(folder, [](nlohmann::json& j) { j["version"] = 2; });
    const std::string message = errorReading(folder.string());
    EXPECT_TRUE(mentions(message, (folder / "recording.json").string())) << message;
    EXPECT_TRUE(mentions(message, "version 2")) << message;
    EXPECT_TRUE(mentions(message, "version 1")) << message;
}

TEST(RecordingErrors, EveryMissingFieldIsNamed) {
    for (const std::string field :
         {"format", "version", "sensor", "width_px", "height_px", "fx_px", "fy_px", "cx_px",
          "cy_px", "depth_unit", "frame_count", "frame_rate_hz"}) {
        const fs::path folder = validRecording("missing_field");
        editJson(folder, [&](nlohmann::json& j) { j.erase(field); });
        const std::string message = errorReading(folder.string());
        EXPECT_TRUE(mentions(message, (folder / "recording.json").string())) << message;
        EXPECT_TRUE(mentions(message, field)) << "without " << field << ": " << message;
    }
}

TEST(RecordingErrors, NegativeZeroOrWronglyTypedFieldsAreNamed) {
    const std::vector<std::pair<std::string, nlohmann::json>> cases = {
        {"width_px", -640},
        {"height_px", 0},
        {"frame_count", -1},
        {"frame_count", 0},
        {"frame_rate_hz", -30.0},
        {"frame_rate_hz", 0},
        {"width_px", 16.5},
        {"width_px", "16"},
        {"sensor", 7},
        {"depth_unit", "inches"},
        {"depth_unit", 1},
        {"version", "1"},
        {"width_px", 1e30},
        {"frame_count", 18446744073709551615u},
        {"fx_px", "fourteen"},
        {"frame_rate_hz", nullptr}};
    for (const auto& [field, value] : cases) {
        const fs::path folder = validRecording("bad_field");
        editJson(folder, [&](nlohmann::json& j) { j[field] = value; });
        const std::string message = errorReading(folder.string());
        EXPECT_TRUE(mentions(message, (folder / "recording.json").string())) << message;
        EXPECT_TRUE(mentions(message, field)) << field << " = " << value << ": " << message;
    }
}

TEST(RecordingErrors, NonPositiveOrNonFiniteIntrinsicsAreNamed) {
    for (const auto& [field, text] :
         std::vector<std::pair<std::string, std::string>>{{"fx_px", "-14"},
                                                          {"fy_px", "0"},
                                                          {"fx_px", "1e39"},
                                                          {"cy_px", "-1e300"},
                                                          {"fx_px", "1e400"}}) {
        const fs::path folder = validRecording("intrinsics");
        // Written as text: JSON has no NaN or infinity, but 1e39 overflows a float.
        nlohmann::json j = nlohmann::json::parse(slurp(folder / "recording.json"));
        j[field] = 12345;
        std::string json = j.dump();
        json.replace(json.find("12345"), 5, text);
        spit(folder / "recording.json", json);
        const std::string message = errorReading(folder.string());
        EXPECT_TRUE(mentions(message, (folder / "recording.json").string())) << message;
        // 1e400 overflows even a double: the JSON reader itself names the offending text.
        EXPECT_TRUE(mentions(message, text == "1e400" ? text : field))
            << field << " = " << text << ": " << message;
    }
}

TEST(RecordingErrors, OptionsThatContradictRecordingJsonAreRefused) {
    const fs::path folder = validRecording("contradiction");
    SourceOptions otherUnit, otherIntrinsics;
    otherUnit.depthUnit = DepthUnit::FifthMillimetre;
    otherIntrinsics.intrinsics = parseIntrinsics("525,525,319.5,239.5");
    std::string message = errorReading(folder.string(), otherUnit);
    EXPECT_TRUE(mentions(message, "--depth-unit")) << message;
    message = errorReading(folder.string(), otherIntrinsics);
    EXPECT_TRUE(mentions(message, "--intrinsics")) << message;
    // Options that agree are fine.
    const auto source = openDepthSource(folder.string(), plainOptions());
    EXPECT_EQ(source->info().frameCount, 2);
}
