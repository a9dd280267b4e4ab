#pragma once
// A simulated structured-light depth camera (PrimeSense / Kinect v1 class): triangle meshes in
// camera space are rasterised on the CPU into exact depth and a label image, then the noise
// model below turns exact depth into what such a sensor reports. This is the ground truth
// behind every accuracy test. Each noise term can be switched off or scaled.
//
// Order in which the terms act on a frame (each one reads the result of the previous):
//   1. rasterise: exact depth, label and surface normal of the nearest surface per pixel;
//   2. range: exact depth outside [minDepth_m, maxDepth_m] reads 0;
//   3. shadows: pixels the projector cannot light (occluded from x = +baseline_m) read 0;
//   4. grazing dropout: pixels whose incidence angle exceeds maxIncidence_deg read 0;
//   5. lateral: near depth discontinuities a pixel reports the reading of a neighbour displaced
//      by N(0, lateral_px) px, which makes silhouettes ragged;
//   6. flying pixels: a reading on a foreground/background edge moves to a depth between the
//      two surfaces, with probability flyingPixelRate;
//   7. axial: Gaussian noise N(0, sigma_z(z, theta)) along the ray;
//   8. quantisation: depth snapped to 1/subpixel px steps of disparity;
//   9. output: rounded to millimetres, 0 outside the working range.
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
    // Axial noise, Nguyen, Izadi & Lovell 2012, Eq. 5 (theta < 60 deg):
    //   sigma_z(z) = 0.0012 + 0.0019 (z - 0.4)^2 m, plus their grazing-angle term
    //   0.0001 / sqrt(z) * theta^2 / (pi/2 - theta)^2 beyond 60 deg.
    bool axial = true;
    float axialScale = 1.0f;  // multiplies sigma_z (e.g. 0.5 for a better-than-Kinect sensor)
    // Lateral noise: ~0.8 px standard deviation of the silhouette edge (same source, Fig. 8).
    bool lateral = true;
    float lateral_px = 0.8f;
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
};

// Standard deviation of axial noise in metres at depth z (m) and incidence angle theta (rad),
// Nguyen, Izadi & Lovell 2012, Eq. 5 (with their grazing term beyond 60 deg).
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
