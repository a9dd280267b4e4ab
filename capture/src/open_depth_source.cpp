#include <algorithm>
#include <cctype>
#include <system_error>

#include "depth_png.h"
#include "meadow/capture/depth_source.h"
#include "meadow/capture/error.h"
#include "openni_source.h"
#include "recording_json.h"
#include "recording_source.h"

namespace meadow::capture {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kOpenNiScheme = "openni://";
const char* kWhatToGive =
    "give a recording folder, a folder of 16-bit PNGs (with --intrinsics and --depth-unit), an "
    ".oni file or openni://";

bool endsWithOni(const std::string& uri) {
    if (uri.size() < 4) return false;
    std::string ext = uri.substr(uri.size() - 4);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".oni";
}

}  // namespace

std::unique_ptr<DepthSource> openDepthSource(const std::string& uri, const SourceOptions& options) {
    if (uri.empty()) throw CaptureError(std::string("no depth source given: ") + kWhatToGive);
    if (uri.starts_with(kOpenNiScheme) || endsWithOni(uri)) return openOpenNiSource(uri);

    const fs::path folder(uri);
    std::error_code ec;
    const fs::file_status status = fs::status(folder, ec);
    if (ec == std::errc::too_many_symbolic_link_levels)
        throw CaptureError(uri + " is a loop of symbolic links: " + kWhatToGive);
    if (!fs::exists(status)) throw CaptureError(uri + " does not exist: " + kWhatToGive);
    if (!fs::is_directory(status)) {
        if (detail::hasPngExtension(folder))
            throw CaptureError(uri +
                               " is a single PNG: give the folder that holds it, with "
                               "--intrinsics fx,fy,cx,cy and --depth-unit mm|0.2mm|m");
        throw CaptureError(uri + " is not a folder: " + kWhatToGive);
    }
    if (fs::exists(folder / detail::kRecordingJsonName, ec))
        return detail::openRecordingFolder(folder, options);
    return detail::openPngFolder(folder, options);
}

}  // namespace meadow::capture
