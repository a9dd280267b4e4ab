#pragma once
// Projector shadow of a structured-light sensor: the pattern comes from a projector beside the
// camera (Kinect v1: baseline_m along +x), so a surface the camera sees but the projector's
// rays cannot reach carries no pattern and reads 0. The band lies on the side of a foreground
// edge away from the projector (the left, -x, for a projector at +x) and is
// baseline * fx * (1/z_fg - 1/z_bg) px wide.
#include <opencv2/core/mat.hpp>
#include <vector>

#include "meadow/capture/intrinsics.h"
#include "meadow/synth/labelled_mesh.h"

namespace meadow::synth::detail {

using capture::Intrinsics;

// 255 where the camera pixel's surface (exact_m > 0) is occluded from the projector at
// (baseline_m, 0, 0), looking along +z like the camera. nearestDepth_m bounds how far the
// projector's view must extend beyond the camera's (disparity fx b / z grows as z shrinks).
cv::Mat1b projectorShadow(const std::vector<LabelledMesh>& meshes, const Intrinsics& camera,
                          const cv::Mat1f& exact_m, float baseline_m, float nearestDepth_m);

}  // namespace meadow::synth::detail
