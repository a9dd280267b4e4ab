#pragma once
// Multipath interference of a time-of-flight camera (Kinect v2 class), as a first-order
// one-bounce model. The camera's emitter lights every visible surface point Q; Q reflects
// diffusely (Lambertian, albedo rho) and part of that light reaches another visible point P, from
// where it returns to the camera with the direct light. P's reading is the phase of the sum; for
// path differences small against the modulation wavelength that is the mean of the paths weighted
// by their irradiance at P:
//   w_Q   = rho / pi * Omega_Q * cos_Q * cos_P * |X_P|^2 / (r^2 cos theta_P)   (indirect / direct)
//   Omega_Q = s^2 (z_Q / |X_Q|)^3 / (fx fy)    solid angle of the emitter's light through Q's
//                                             s x s block of pixels
//   Delta_Q = |X_Q| + r - |X_P|               extra path of the bounce
//   radial lengthening = sum w_Q Delta_Q / (2 (1 + sum w_Q)), turned into z by z_P / |X_P|
// with r = |X_P - X_Q|, cos_Q and cos_P the angles between the surfaces' normals and the segment
// between them (a pair that does not face each other gives nothing), theta_P the incidence of the
// camera ray at P. Two points of one plane never face each other and a convex corner's faces look
// away from each other, so the bias is zero there; at a concave corner (a wall meeting the floor)
// it is largest and fades with distance from it. Sarbolandi et al. 2015 name multipath among the
// Kinect v2's main errors; Fuchs 2010 ("Multipath interference compensation in time-of-flight
// camera images") models it with the same diffuse bounce.
// Not modelled: occlusion between P and Q, more than one bounce, the phase wrapping of long paths.
#include <opencv2/core/mat.hpp>
#include <vector>

#include "meadow/capture/intrinsics.h"

namespace meadow::synth::detail {

using capture::Intrinsics;

// Lengthening of each pixel's reading along z (m, >= 0) for the surfaces of `depth_m` (0 = none)
// with camera-facing unit `normals`. The sum runs over one source per 8 x 8 block of pixels and
// is evaluated on a 4 px grid, interpolated between grid points on the same surface.
cv::Mat1f multipathBias_m(const cv::Mat1f& depth_m, const cv::Mat3f& normals, const Intrinsics& k,
                          float albedo);

// The same sum for one receiving point P (camera space, metres) with unit normal nP, over the
// given sources (points, normals and solid angles): what multipathBias_m evaluates per grid point.
struct MultipathSource {
    cv::Vec3f x_m;
    cv::Vec3f n;
    float solidAngle_sr = 0.f;
    float footprint_m = 0.f;  // a source nearer than this counts as this far (its block's size)
};
float multipathLengthening_m(const cv::Vec3f& xP_m, const cv::Vec3f& nP,
                             const std::vector<MultipathSource>& sources, float albedo);

}  // namespace meadow::synth::detail
