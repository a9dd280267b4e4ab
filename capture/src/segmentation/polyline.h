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

// How far the line's points lie, at most, from the quadratic Bezier through its end points whose
// middle control point fits them best (least squares, the points' parameters corrected to their
// nearest curve points): whether the blade model (J&W, a quadratic spine) can hold the line. A
// quadratic turns less than 180 deg, so an arch that rises and droops fits and a curl that folds
// back does not. Lines of fewer than three points are held exactly (0).
float quadraticBezierMiss_px(const std::vector<cv::Point2f>& line);

}  // namespace meadow::capture::segmentation
