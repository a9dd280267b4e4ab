#include "recording_json.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <system_error>

#include "meadow/capture/error.h"
#include "meadow/capture/recording.h"
#include "meadow/core/json_reader.h"

namespace meadow::capture {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace detail {

namespace {

// Number of digits in a frame file name: depth/000000.png.
constexpr int kFrameNameDigits = 6;

const char* kRecordHint = "fix the file or record again";

// A float field kept as read: a value beyond a float becomes infinity so that
// Intrinsics::problem() reports it with the others.
float floatOrInfinity(const JsonReader& reader, std::string_view key) {
    const double value = reader.number(key);
    if (std::abs(value) <= std::numeric_limits<float>::max()) return static_cast<float>(value);
    return std::copysign(std::numeric_limits<float>::infinity(), value);
}

}  // namespace

fs::path framePath(const fs::path& folder, int index) {
    char name[32];
    std::snprintf(name, sizeof name, "%0*d.png", kFrameNameDigits, index);
    return folder / kDepthFolderName / name;
}

std::string recordingInfoToJson(const RecordingInfo& info) {
    ordered_json j;
    j["format"] = std::string(kRecordingFormatName);
    j["version"] = kRecordingFormatVersion;
    j["sensor"] = info.sensor;
    j["width_px"] = info.intrinsics.width_px;
    j["height_px"] = info.intrinsics.height_px;
    j["fx_px"] = shortestDouble(info.intrinsics.fx_px);
    j["fy_px"] = shortestDouble(info.intrinsics.fy_px);
    j["cx_px"] = shortestDouble(info.intrinsics.cx_px);
    j["cy_px"] = shortestDouble(info.intrinsics.cy_px);
    j["depth_unit"] = toString(info.depthUnit);
    j["frame_count"] = info.frameCount;
    j["frame_rate_hz"] = info.frameRate_hz;
    return j.dump(2) + "\n";
}

RecordingInfo recordingInfoFromJson(const std::string& text, const fs::path& file) {
    try {
        const nlohmann::json j = parseJsonObject(text);
        checkJsonFormat(j, {kRecordingFormatName, kRecordingFormatVersion});
        const JsonReader field(j);
        RecordingInfo info;
        info.sensor = field.string("sensor");
        info.intrinsics.width_px = field.integer("width_px", 1, std::numeric_limits<int>::max());
        info.intrinsics.height_px = field.integer("height_px", 1, std::numeric_limits<int>::max());
        info.intrinsics.fx_px = floatOrInfinity(field, "fx_px");
        info.intrinsics.fy_px = floatOrInfinity(field, "fy_px");
        info.intrinsics.cx_px = floatOrInfinity(field, "cx_px");
        info.intrinsics.cy_px = floatOrInfinity(field, "cy_px");
        if (const std::string problem = info.intrinsics.problem(); !problem.empty())
            throw CaptureError(file.string() + ": intrinsics unusable: " + problem + "; " +
                               kRecordHint);
        const std::string unit = field.string("depth_unit");
        const std::optional<DepthUnit> depthUnit = parseDepthUnit(unit);
        if (!depthUnit)
            field.fail("depth_unit",
                       "must be " + kDepthUnitNames.list(", ") + ", got \"" + unit + "\"");
        info.depthUnit = *depthUnit;
        info.frameCount = field.integer("frame_count", 1, std::numeric_limits<int>::max());
        info.frameRate_hz = field.number("frame_rate_hz");
        if (info.frameRate_hz <= 0.0)
            field.fail("frame_rate_hz", "must be a positive number of frames per second, got " +
                                            std::to_string(info.frameRate_hz));
        return info;
    } catch (const JsonError& e) {
        switch (e.kind()) {
            case JsonError::Kind::WrongFormat:
                throw CaptureError(file.string() + ": " + e.what() +
                                   ": this is not a meadow recording; give a recording folder, "
                                   "or a plain PNG folder with --intrinsics and --depth-unit");
            case JsonError::Kind::WrongVersion:
                throw CaptureError(file.string() + ": " + e.what() +
                                   "; use the meadow that wrote it or record again");
            default:
                throw CaptureError(file.string() + ": " + e.what() + "; " + kRecordHint);
        }
    }
}

bool isRecordingJson(const fs::path& file) {
    try {
        const nlohmann::json j = parseJsonObject(readTextFile(file));
        const auto format = j.find("format");
        return format != j.end() && format->is_string() &&
               format->get<std::string>() == kRecordingFormatName;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace detail

RecordingInfo readRecordingInfo(const fs::path& folder) {
    std::error_code ec;
    (void)fs::status(folder, ec);
    if (ec == std::errc::too_many_symbolic_link_levels)
        throw CaptureError(folder.string() +
                           " is a loop of symbolic links: give the folder of a meadow recording");
    if (!fs::exists(folder, ec))
        throw CaptureError(folder.string() +
                           " does not exist: give the folder of a meadow recording");
    if (!fs::is_directory(folder, ec))
        throw CaptureError(folder.string() +
                           " is not a folder: give the folder of a meadow recording");
    const fs::path file = folder / detail::kRecordingJsonName;
    if (!fs::is_regular_file(file, ec))
        throw CaptureError(file.string() +
                           " is missing: this is not a finished meadow recording; for a plain "
                           "folder of 16-bit PNGs pass --intrinsics fx,fy,cx,cy and "
                           "--depth-unit mm|0.2mm|m");
    std::string text;
    try {
        text = readTextFile(file);
    } catch (const Error& e) {
        throw CaptureError(e.what());
    }
    return detail::recordingInfoFromJson(text, file);
}

}  // namespace meadow::capture
