#pragma once
#include <opencv2/core/mat.hpp>

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

}  // namespace meadow::capture
