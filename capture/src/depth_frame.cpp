#include "meadow/capture/depth_frame.h"

#include <opencv2/core.hpp>

namespace meadow::capture {

namespace {
// No depth camera meadow reads reaches this far.
constexpr int kFarthestReading_mm = 20000;
}  // namespace

std::string implausibleDepthProblem(const DepthFrame& frame) {
    const int valid = cv::countNonZero(frame.depth_mm);
    const int far = cv::countNonZero(frame.depth_mm > kFarthestReading_mm);
    if (valid == 0 || 2 * far <= valid) return {};
    double largest_mm = 0;
    cv::minMaxLoc(frame.depth_mm, nullptr, &largest_mm);
    return "frame " + std::to_string(frame.index) + ": " + std::to_string(far) + " of " +
           std::to_string(valid) + " readings lie beyond " +
           std::to_string(kFarthestReading_mm / 1000) + " m (up to " +
           std::to_string(static_cast<int>(largest_mm / 1000)) +
           " m), farther than any depth camera reads: the values look bit-rotated or in another "
           "unit; pass --depth-unit (mm, 0.2mm or m) or convert the frames";
}

}  // namespace meadow::capture
