#pragma once
// The plain baseline meadow's capture is held against on real plants: a plant's leaves counted in
// one depth frame as the end points of its skeleton. The depth band is given (as a user of such a
// counter sets it around the plant); the band's largest region in the middle half of the image is
// cleaned (opened, closed), thinned (OpenCV's Zhang-Suen) and its skeleton's end points (one
// neighbour) counted, less one for the stem's foot.
#include <opencv2/core/mat.hpp>

namespace meadow::synth {

[[nodiscard]] int countLeavesPlainly(const cv::Mat1w& depth_mm, float near_m, float far_m);

}  // namespace meadow::synth
