#include "recording_json.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

#include "meadow/capture/error.h"
#include "meadow/capture/recording.h"

namespace meadow::capture {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

namespace detail {

namespace {

// Number of digits in a frame file name: depth/000000.png.
constexpr int kFrameNameDigits = 6;

const char* kRecordHint = "fix the file or record again";

// A float as JSON: the shortest decimal that reads back as the same float (575.8, not
// 575.7999877929688), so recording.json stays readable and round trips bit for bit.
double shortestDouble(float value) {
    char text[32];
    const auto [end, ec] = std::to_chars(std::begin(text), std::end(text), value);
    if (ec != std::errc{}) return value;
    double result = value;
    std::from_chars(text, end, result);
    return result;
}

// Each accessor throws CaptureError naming the file, the field and what it expected.
class FieldReader {
public:
    FieldReader(const ordered_json& object, const fs::path& file) : j_(object), file_(file) {}

    [[noreturn]] void fail(const std::string& field, const std::string& problem) const {
        throw CaptureError(file_.string() + ": \"" + field + "\" " + problem + "; " + kRecordHint);
    }

    const ordered_json& require(const std::string& field) const {
        const auto it = j_.find(field);
        if (it == j_.end()) fail(field, "is missing");
        return *it;
    }

    std::string string(const std::string& field) const {
        const ordered_json& v = require(field);
        if (!v.is_string()) fail(field, "must be a string, got " + v.dump());
        return v.get<std::string>();
    }

    std::int64_t integer(const std::string& field) const {
        const ordered_json& v = require(field);
        if (v.is_number_unsigned() &&
            v.get<std::uint64_t>() >
                static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
            fail(field, "is too large, got " + v.dump());
        if (!v.is_number_integer()) fail(field, "must be an integer, got " + v.dump());
        return v.get<std::int64_t>();
    }

    int positiveInt(const std::string& field) const {
        const std::int64_t value = integer(field);
        if (value <= 0) fail(field, "must be positive, got " + std::to_string(value));
        if (value > std::numeric_limits<int>::max())
            fail(field, "is too large, got " + std::to_string(value));
        return static_cast<int>(value);
    }

    double number(const std::string& field) const {
        const ordered_json& v = require(field);
        if (!v.is_number()) fail(field, "must be a number, got " + v.dump());
        return v.get<double>();
    }

    // Out-of-range values become infinity so that Intrinsics::problem() reports them.
    float floatNumber(const std::string& field) const {
        const double value = number(field);
        if (std::isfinite(value) && std::abs(value) <= std::numeric_limits<float>::max())
            return static_cast<float>(value);
        return std::isnan(value) ? std::numeric_limits<float>::quiet_NaN()
                                 : std::copysign(std::numeric_limits<float>::infinity(), value);
    }

private:
    const ordered_json& j_;
    const fs::path& file_;
};

ordered_json parseObject(const std::string& text, const fs::path& file) {
    ordered_json j;
    try {
        j = ordered_json::parse(text);
    } catch (const ordered_json::exception& e) {  // parse_error, or out_of_range for 1e400
        throw CaptureError(file.string() + " is not valid JSON (" + e.what() + "); " + kRecordHint);
    }
    if (!j.is_object())
        throw CaptureError(file.string() + " must hold a JSON object, got " +
                           std::string(j.type_name()) + "; " + kRecordHint);
    return j;
}

std::string slurp(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw CaptureError("cannot read " + file.string() + ": check that it is readable");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
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
    const ordered_json j = parseObject(text, file);
    const FieldReader field(j, file);

    const ordered_json& format = field.require("format");
    if (!format.is_string() || format.get<std::string>() != kRecordingFormatName)
        throw CaptureError(file.string() + ": format is " + format.dump() + ", expected \"" +
                           std::string(kRecordingFormatName) +
                           "\": this is not a meadow recording; give a recording folder, or a "
                           "plain PNG folder with --intrinsics and --depth-unit");
    const std::int64_t version = field.integer("version");
    if (version != kRecordingFormatVersion)
        throw CaptureError(file.string() + ": version " + std::to_string(version) +
                           " is not supported (this meadow reads version " +
                           std::to_string(kRecordingFormatVersion) +
                           "); use the meadow that wrote it or record again");

    RecordingInfo info;
    info.sensor = field.string("sensor");
    info.intrinsics.width_px = field.positiveInt("width_px");
    info.intrinsics.height_px = field.positiveInt("height_px");
    info.intrinsics.fx_px = field.floatNumber("fx_px");
    info.intrinsics.fy_px = field.floatNumber("fy_px");
    info.intrinsics.cx_px = field.floatNumber("cx_px");
    info.intrinsics.cy_px = field.floatNumber("cy_px");
    if (const std::string problem = info.intrinsics.problem(); !problem.empty())
        throw CaptureError(file.string() + ": intrinsics unusable: " + problem + "; " +
                           kRecordHint);
    const std::string unit = field.string("depth_unit");
    const std::optional<DepthUnit> depthUnit = parseDepthUnit(unit);
    if (!depthUnit)
        field.fail("depth_unit", "must be \"mm\", \"0.2mm\" or \"m\", got \"" + unit + "\"");
    info.depthUnit = *depthUnit;
    info.frameCount = field.positiveInt("frame_count");
    info.frameRate_hz = field.number("frame_rate_hz");
    if (!std::isfinite(info.frameRate_hz) || info.frameRate_hz <= 0.0)
        field.fail("frame_rate_hz", "must be a positive number of frames per second, got " +
                                        std::to_string(info.frameRate_hz));
    return info;
}

bool isRecordingJson(const fs::path& file) {
    try {
        const ordered_json j = ordered_json::parse(slurp(file));
        return j.is_object() && j.contains("format") && j["format"].is_string() &&
               j["format"].get<std::string>() == kRecordingFormatName;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace detail

RecordingInfo readRecordingInfo(const fs::path& folder) {
    std::error_code ec;
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
    return detail::recordingInfoFromJson(detail::slurp(file), file);
}

}  // namespace meadow::capture
