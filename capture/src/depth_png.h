#pragma once
// Private PNG helpers for depth frames: OpenCV does the encoding and decoding; these add the
// checks and the one-line messages (which file, what is wrong, what to do).
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "meadow/capture/recording_info.h"

namespace meadow::capture::detail {

// PNG bytes of a 16-bit single-channel image. Throws CaptureError naming `forFile` if OpenCV
// cannot encode it.
std::vector<unsigned char> encodeDepthPng(const cv::Mat1w& depth,
                                          const std::filesystem::path& forFile);

// The stored integers of a 16-bit single-channel PNG, unconverted. Throws CaptureError naming
// the file when it cannot be read, is empty, is not a PNG, is truncated or corrupt, or is not
// 16-bit single-channel.
cv::Mat1w readDepthPng(const std::filesystem::path& file);
// The same for a file's bytes already read; `file` names it in messages.
cv::Mat1w decodeDepthPng(const std::vector<unsigned char>& bytes,
                         const std::filesystem::path& file);

// Stored integers in `unit` -> millimetres (rounded). Values that do not fit in 16-bit
// millimetres (beyond 65.535 m, only possible in metre units) become 0, "no reading".
cv::Mat1w toMillimetres(const cv::Mat1w& stored, DepthUnit unit);

// True for "x.png" / "x.PNG" (any case).
bool hasPngExtension(const std::filesystem::path& file);

// The regular *.png files directly in `folder`, sorted by name.
std::vector<std::filesystem::path> listPngFiles(const std::filesystem::path& folder);

}  // namespace meadow::capture::detail
