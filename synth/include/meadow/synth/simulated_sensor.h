#pragma once
// A simulated depth camera: triangle meshes in camera space are rasterised on the CPU into exact
// depth and a label image, then the noise model below turns exact depth into what a sensor
// reports. NoiseModel's defaults are a structured-light PrimeSense / Kinect v1 class camera;
// sensor_models.h holds calibrated Kinect v1, Kinect v2 (time of flight) and RealSense D435
// (active stereo) models. This is the ground truth behind every accuracy test. Each noise term
// can be switched off or scaled.
//
// Order in which the terms act on a frame (each one reads the result of the previous):
//   1. rasterise: exact depth, label and surface normal of the nearest surface per pixel;
//   2. range: exact depth outside [minDepth_m, maxDepth_m] reads 0;
//   3. shadows: pixels the projector cannot light (occluded from x = +baseline_m) read 0;
//   4. grazing dropout: pixels whose incidence angle exceeds maxIncidence_deg read 0;
//   5. edge fattening: a reading behind a depth edge within edgeFattening_px of the nearer
//      surface reads that surface (a stereo matcher's window);
//   6. lateral: near depth discontinuities a pixel reports the reading of a neighbour displaced
//      by N(0, lateral_px) px, drawn per pixel or as a field correlated over
//      lateralCorrelation_px, which makes silhouettes ragged;
//   7. flying pixels: a reading on a foreground/background edge moves to a depth between the
//      two surfaces, with probability flyingPixelRate;
//   8. multipath: light that reaches a surface by way of another one lengthens its reading
//      (time of flight, concave corners);
//   9. axial: Gaussian noise N(0, sigma_z(z, theta)) along the ray;
//  10. quantisation: depth snapped to 1/subpixel px steps of disparity;
//  11. output: rounded to millimetres, 0 outside the working range.
// Random terms draw from a counter-based generator keyed by (seed, term, pixel), so a frame is
// bit-identical for a seed whatever the order or threading of the loops.
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "meadow/capture/intrinsics.h"
#include "meadow/synth/labelled_mesh.h"

namespace meadow::synth {

using capture::Intrinsics;

struct NoiseModel {
    // Axial noise, in the form of Nguyen, Izadi & Lovell 2012, Eq. 5 (their figures are the
    // defaults): below 60 deg
    //   sigma_z = axialBase_m + axialQuadratic_per_m (z - axialVertex_m)^2,
    // plus, beyond 60 deg, axialGrazing_m z^axialGrazingDepthPower theta^2 / (pi/2 - theta)^2
    // (Nguyen: 0.0001 m / sqrt(z)). Fankhauser et al. 2015's Kinect v2 model and the stereo RMS
    // error z^2 subpixel / (f b) take the same form (sensor_models.cpp).
    bool axial = true;
    float axialScale = 1.0f;  // multiplies sigma_z (e.g. 0.5 for a better-than-Kinect sensor)
    float axialBase_m = 0.0012f;
    float axialQuadratic_per_m = 0.0019f;  // m per m^2
    float axialVertex_m = 0.4f;
    float axialGrazing_m = 0.0001f;  // m at z = 1 m
    float axialGrazingDepthPower = -0.5f;
    // Lateral noise: ~0.8 px standard deviation of the silhouette edge (same source, Fig. 8).
    // With lateralCorrelation_px = 0 each pixel draws its own displacement; above 0 the
    // displacements are a Gaussian random field with that correlation length (the sigma of the
    // Gaussian that smooths white noise), so an edge moves in stretches, as a block matcher's
    // window moves it.
    bool lateral = true;
    float lateral_px = 0.8f;
    float lateralCorrelation_px = 0.f;
    // Structured-light disparity quantisation: depth is snapped to steps of 1/8 px of
    // disparity d = fx * b / z with baseline b, so steps grow as z^2 / (8 fx b).
    bool quantisation = true;
    float baseline_m = 0.075f;  // also places the projector (at x = +baseline_m) for shadows
    float subpixel = 8.0f;
    // Missing readings: projector shadow beside depth discontinuities and surfaces seen at
    // grazing angles (> maxIncidence_deg) read 0.
    bool shadows = true;
    bool grazingDropout = true;
    float maxIncidence_deg = 80.0f;
    // Flying pixels: a fraction of the pixels on a foreground/background edge read a depth
    // between the two surfaces. Only pixels where something was rendered fly, so a pixel that
    // saw nothing never gets a reading from this term (it can from lateral noise).
    bool flyingPixels = true;
    float flyingPixelRate = 0.3f;
    // Edge fattening of a stereo matcher: a pixel whose reading lies behind a depth edge (or
    // that has none) within edgeFattening_px (Euclidean) of a nearer reading takes the nearest
    // such reading, as the correlation window there is dominated by the nearer surface.
    bool edgeFattening = false;
    float edgeFattening_px = 0.f;
    // Multipath of a time-of-flight camera: each reading is lengthened by the light that
    // reaches its surface after one diffuse bounce off another visible surface (Lambertian, of
    // albedo multipathAlbedo), the phase of the sum read as a weighted mean of the path
    // lengths; visibility between the two surfaces is not tested. Zero on a plane and at convex
    // corners, largest at concave ones (a wall meeting the floor). See sensor_noise_multipath.h.
    bool multipath = false;
    float multipathAlbedo = 0.f;
    // Global multiplier on every random term (0 = exact depth, still quantised if enabled).
    float scale = 1.0f;
    // Working range; outside it the sensor reads 0.
    float minDepth_m = 0.4f;
    float maxDepth_m = 8.0f;

    // Every term off: exact depth in mm (rounded). The working range is widened to what a
    // uint16 millimetre image can hold, so ground truth is not cut at 0.4 m.
    static NoiseModel none();
    // Empty when usable; otherwise what is wrong ("flyingPixelRate must be in [0, 1], got 2").
    [[nodiscard]] std::string problem() const;
    // Standard deviation of axial noise in metres at depth z (m) and incidence angle theta
    // (rad), from the axial coefficients above (axialScale and scale not applied).
    [[nodiscard]] float axialSigma_m(float z_m, float incidence_rad) const;
};

// Standard deviation of axial noise in metres at depth z (m) and incidence angle theta (rad),
// Nguyen, Izadi & Lovell 2012, Eq. 5 (with their grazing term beyond 60 deg): NoiseModel's
// defaults.
float axialSigma_m(float z_m, float incidence_rad);

// Depth step (m) between neighbouring quantised disparities at depth z: z^2 / (subpixel fx b).
float disparityStep_m(float z_m, float fx_px, float baseline_m, float subpixel);

struct SimulatedFrame {
    cv::Mat1w depth_mm;       // what the sensor reports, 0 = no reading
    cv::Mat1f exact_m;        // noise-free depth of the nearest surface, 0 where nothing
    cv::Mat1w labels;         // label of the nearest surface per pixel (LabelledMesh::label)
    cv::Mat3f normals;        // camera-space unit normal of that surface, facing the camera
    cv::Mat1f incidence_rad;  // angle between that normal and the pixel's viewing ray
};

class SimulatedSensor {
public:
    // Throws std::invalid_argument naming the problem when intrinsics or noise are unusable.
    explicit SimulatedSensor(Intrinsics intrinsics = Intrinsics::kinectV1(), NoiseModel noise = {});
    // Deterministic: the same meshes and seed give the same frame, bit for bit.
    // Throws std::invalid_argument when a mesh has an out-of-range index or a non-finite vertex.
    [[nodiscard]] SimulatedFrame render(const std::vector<LabelledMesh>& meshes,
                                        std::uint64_t seed) const;
    [[nodiscard]] const Intrinsics& intrinsics() const { return intrinsics_; }
    [[nodiscard]] const NoiseModel& noise() const { return noise_; }

private:
    Intrinsics intrinsics_;
    NoiseModel noise_;
};

}  // namespace meadow::synth
