#pragma once
// The simulated sensor's noise terms that act at depth discontinuities: lateral (silhouette)
// noise and flying pixels. Both follow the same definition of an edge.
#include <cstdint>
#include <opencv2/core/mat.hpp>

namespace meadow::synth::detail {

// Two 4-neighbours straddle a depth discontinuity when exactly one of them saw a surface, or
// when their depths differ by more than this fraction of the nearer one. 3 % is ~17 px of
// depth step at 1 m, far more than any surface short of ~85 deg incidence changes per pixel.
constexpr float kDepthJumpRelative = 0.03f;
bool isDepthJump(float a_m, float b_m);

// 255 where a pixel has a 4-neighbour across a depth discontinuity (on both sides of it).
cv::Mat1b depthDiscontinuities(const cv::Mat1f& surface_m);

// The state the edge terms transform: the surface each pixel sees (exact depth, 0 = none), the
// reading it would report so far (0 = dropped), and the incidence angle that goes with it.
struct EdgeState {
    cv::Mat1f surface_m;
    cv::Mat1f reading_m;
    cv::Mat1f incidence_rad;
};

// Lateral noise, Nguyen, Izadi & Lovell 2012, lateral model (sigma_L ~ 0.8 px at an edge): every
// pixel within 3 sigma of a discontinuity (of the surfaces, or of the readings, so shadow and
// dropout borders too) reports what the pixel displaced by (round(sigma u), round(sigma v))
// sees, so silhouettes become ragged by ~sigma. With correlation_px = 0, u and v are drawn
// N(0, 1) per pixel; above 0 they are white noise smoothed by a Gaussian of that sigma and
// scaled back to unit variance, so neighbouring pixels along an edge move together.
void applyLateralNoise(EdgeState& state, float sigma_px, float correlation_px, std::uint64_t seed);

// Edge fattening (stereo): every pixel whose reading is missing, or lies behind a depth jump,
// within width_px (Euclidean) of a nearer reading takes the nearest such reading and its
// incidence angle. Deterministic. Returns how many pixels were fattened.
int applyEdgeFattening(EdgeState& state, float width_px);

// Flying pixels: with probability rate, a pixel with a reading that borders a discontinuity
// to another surface reads a depth uniformly between its own and that surface's (the larger
// jump if several), as the correlation window of a structured-light matcher mixes both.
// Returns how many pixels flew.
int applyFlyingPixels(EdgeState& state, float rate, std::uint64_t seed);

}  // namespace meadow::synth::detail
