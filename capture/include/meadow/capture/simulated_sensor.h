#pragma once
// A simulated structured-light depth camera (PrimeSense / Kinect v1 class): triangle meshes in
// camera space are rasterised on the CPU into exact depth and a label image, then the noise
// model below turns exact depth into what such a sensor reports. This is the ground truth
// behind every accuracy test. Each noise term can be switched off or scaled.
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "meadow/capture/intrinsics.h"
#include "meadow/capture/mesh.h"

namespace meadow::capture {

struct NoiseModel {
    // Axial noise, Nguyen, Izadi & Lovell 2012, Eq. 5 (theta < 60 deg):
    //   sigma_z(z) = 0.0012 + 0.0019 (z - 0.4)^2 m, plus their grazing-angle term
    //   0.0001 / sqrt(z) * theta^2 / (pi/2 - theta)^2 beyond 60 deg.
    bool axial = true;
    // Lateral noise: ~0.8 px standard deviation of the silhouette edge (same source, Fig. 8).
    bool lateral = true;
    float lateral_px = 0.8f;
    // Structured-light disparity quantisation: depth is snapped to steps of 1/8 px of
    // disparity d = fx * b / z with baseline b, so steps grow as z^2 / (8 fx b).
    bool quantisation = true;
    float baseline_m = 0.075f;
    float subpixel = 8.0f;
    // Missing readings: projector shadow beside depth discontinuities and surfaces seen at
    // grazing angles (> maxIncidence_deg) read 0.
    bool shadows = true;
    bool grazingDropout = true;
    float maxIncidence_deg = 80.0f;
    // Flying pixels: a fraction of the pixels on a foreground/background edge read a depth
    // between the two surfaces.
    bool flyingPixels = true;
    float flyingPixelRate = 0.3f;
    // Global multiplier on every random term (0 = exact depth, still quantised if enabled).
    float scale = 1.0f;
    // Working range; outside it the sensor reads 0.
    float minDepth_m = 0.4f;
    float maxDepth_m = 8.0f;

    static NoiseModel none();  // every term off: exact depth in mm (rounded)
};

// Standard deviation of axial noise in metres at depth z (m) and incidence angle theta (rad).
float axialSigma_m(float z_m, float incidence_rad);

struct SimulatedFrame {
    cv::Mat1w depth_mm;  // what the sensor reports, 0 = no reading
    cv::Mat1f exact_m;   // noise-free depth of the nearest surface, 0 where nothing
    cv::Mat1w labels;    // label of the nearest surface per pixel (LabelledMesh::label)
};

class SimulatedSensor {
public:
    explicit SimulatedSensor(Intrinsics intrinsics = Intrinsics::kinectV1(), NoiseModel noise = {});
    // Deterministic: the same meshes and seed give the same frame, bit for bit.
    [[nodiscard]] SimulatedFrame render(const std::vector<LabelledMesh>& meshes,
                                        std::uint64_t seed) const;
    [[nodiscard]] const Intrinsics& intrinsics() const { return intrinsics_; }
    [[nodiscard]] const NoiseModel& noise() const { return noise_; }

private:
    Intrinsics intrinsics_;
    NoiseModel noise_;
};

}  // namespace meadow::capture
