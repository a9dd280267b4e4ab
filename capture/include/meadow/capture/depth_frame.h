#pragma once
#include <opencv2/core/mat.hpp>
#include <string>

#include "meadow/capture/intrinsics.h"

namespace meadow::capture {

// One depth image: millimetres as uint16, 0 = no reading. Every source converts its native
// unit (0.2 mm for TUM, metres for float images) to this once, on reading.
struct DepthFrame {
    cv::Mat1w depth_mm;
    Intrinsics intrinsics;
    double timestamp_s = 0.0;
    int index = 0;  // position in its source, from 0
};

// "" when the frame's readings look like depths; otherwise what is wrong and what to do: most
// readings lie farther than any depth camera reads (bit-rotated PNGs of some data sets, or
// values in another unit than the one stated).
[[nodiscard]] std::string implausibleDepthProblem(const DepthFrame& frame);

}  // namespace meadow::capture
