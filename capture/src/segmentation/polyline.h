#pragma once
// Internal: points along an open polyline by arc length, for the stages that follow a blade's
// sides (blade_flags.cpp, fork_partition.cpp).
#include <opencv2/core/types.hpp>
#include <vector>

namespace meadow::capture::segmentation {

// `count` (>= 2) points at equal arc-length steps from the line's first point to its last.
std::vector<cv::Point2f> resampledEvenly(const std::vector<cv::Point2f>& line, int count);
// Points every `step_px` of arc length from the line's first point, as far as the line goes.
std::vector<cv::Point2f> resampledEvery(const std::vector<cv::Point2f>& line, float step_px);

}  // namespace meadow::capture::segmentation
