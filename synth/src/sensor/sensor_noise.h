#pragma once
// Per-pixel terms of the simulated sensor's noise model (see simulated_sensor.h for the order
// in which they act). Image-wide terms live in sensor_noise_edges.h and sensor_noise_shadow.h.
#include <opencv2/core/matx.hpp>

#include "meadow/capture/intrinsics.h"
#include "meadow/synth/simulated_sensor.h"

namespace meadow::synth::detail {

using capture::Intrinsics;

// Angle (rad, in [0, pi/2]) between a surface's unit normal and the viewing ray through pixel
// (u, v). Nguyen et al. 2012 measure theta between the normal and the camera axis on targets
// at the image centre, where the two agree; per pixel, the ray is what the light follows.
float incidenceAngle_rad(const cv::Vec3f& normal, float u_px, float v_px, const Intrinsics& k);

// Disparity quantisation of a structured-light sensor: the matcher resolves disparity
// d = fx b / z to 1/subpixel px, so depth snaps to z' = fx b / (round(d subpixel) / subpixel).
// Returns 0 (no reading) when the disparity rounds to 0 (beyond any usable range).
float quantiseDepth_m(float z_m, float fx_px, float baseline_m, float subpixel);

}  // namespace meadow::synth::detail
