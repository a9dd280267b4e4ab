#pragma once
// Private: the layout of a recording folder and the JSON of recording.json.
#include <filesystem>
#include <string>

#include "meadow/capture/recording_info.h"

namespace meadow::capture::detail {

inline constexpr const char* kRecordingJsonName = "recording.json";
inline constexpr const char* kDepthFolderName = "depth";

// folder/depth/000042.png for index 42.
std::filesystem::path framePath(const std::filesystem::path& folder, int index);

// recording.json text (format name and version first, then the info, one field per line).
std::string recordingInfoToJson(const RecordingInfo& info);

// Parses and checks recording.json text; messages name `file`.
RecordingInfo recordingInfoFromJson(const std::string& text, const std::filesystem::path& file);

// True when `file` is a JSON object whose "format" is "meadow.recording" (any version):
// what the writer accepts to overwrite.
bool isRecordingJson(const std::filesystem::path& file);

}  // namespace meadow::capture::detail
