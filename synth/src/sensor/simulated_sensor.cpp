#include "meadow/synth/simulated_sensor.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rasteriser.h"
#include "sensor_noise.h"
#include "sensor_noise_edges.h"
#include "sensor_noise_multipath.h"
#include "sensor_noise_rng.h"
#include "sensor_noise_shadow.h"

namespace meadow::synth {
namespace {

constexpr float kMillimetresPerMetre = 1000.f;
constexpr float kRadiansPerDegree = std::numbers::pi_v<float> / 180.f;

// Steps 2-4 of simulated_sensor.h: what the sensor could read before edge effects and noise.
detail::EdgeState observable(const detail::RasterImage& raster, const cv::Mat1b& shadow,
                             const Intrinsics& k, const NoiseModel& noise,
                             cv::Mat1f& incidence_rad) {
    const float maxIncidence_rad = noise.maxIncidence_deg * kRadiansPerDegree;
    detail::EdgeState state{raster.depth_m.clone(), cv::Mat1f::zeros(raster.depth_m.size()),
                            cv::Mat1f::zeros(raster.depth_m.size())};
    for (int y = 0; y < k.height_px; ++y)
        for (int x = 0; x < k.width_px; ++x) {
            const float z_m = raster.depth_m(y, x);
            if (z_m <= 0.f) continue;
            const float theta = detail::incidenceAngle_rad(
                raster.normals(y, x), static_cast<float>(x), static_cast<float>(y), k);
            incidence_rad(y, x) = theta;
            state.incidence_rad(y, x) = theta;
            if (z_m < noise.minDepth_m || z_m > noise.maxDepth_m) continue;
            if (noise.shadows && shadow(y, x)) continue;
            if (noise.grazingDropout && theta > maxIncidence_rad) continue;
            state.reading_m(y, x) = z_m;
        }
    return state;
}

}  // namespace

SimulatedSensor::SimulatedSensor(Intrinsics intrinsics, NoiseModel noise)
    : intrinsics_(intrinsics), noise_(noise) {
    if (const std::string problem = intrinsics_.problem(); !problem.empty())
        throw std::invalid_argument("SimulatedSensor: invalid intrinsics: " + problem);
    if (const std::string problem = noise_.problem(); !problem.empty())
        throw std::invalid_argument("SimulatedSensor: invalid noise model: " + problem);
}

SimulatedFrame SimulatedSensor::render(const std::vector<LabelledMesh>& meshes,
                                       std::uint64_t seed) const {
    for (std::size_t i = 0; i < meshes.size(); ++i)
        if (const std::string problem = detail::meshProblem(meshes[i], i); !problem.empty())
            throw std::invalid_argument("SimulatedSensor::render: " + problem);

    const Intrinsics& k = intrinsics_;
    const NoiseModel& n = noise_;
    // 1. Exact depth, labels and normals of the nearest surface.
    detail::RasterImage raster = detail::rasterise(meshes, k, {0.f, 0.f, 0.f}, true);
    SimulatedFrame frame;
    frame.exact_m = raster.depth_m;
    frame.labels = raster.labels;
    frame.normals = raster.normals;
    frame.incidence_rad = cv::Mat1f::zeros(k.height_px, k.width_px);

    // 2-4. Range, projector shadow, grazing dropout.
    const cv::Mat1b shadow =
        n.shadows ? detail::projectorShadow(meshes, k, raster.depth_m, n.baseline_m, n.minDepth_m)
                  : cv::Mat1b::zeros(k.height_px, k.width_px);
    detail::EdgeState state = observable(raster, shadow, k, n, frame.incidence_rad);

    // 5-7. Edge effects.
    if (n.edgeFattening) (void)detail::applyEdgeFattening(state, n.edgeFattening_px);
    if (n.lateral)
        detail::applyLateralNoise(state, n.scale * n.lateral_px, n.lateralCorrelation_px, seed);
    if (n.flyingPixels)
        (void)detail::applyFlyingPixels(state, std::min(1.f, n.scale * n.flyingPixelRate), seed);

    // 8. Multipath: a bias of the surface each pixel sees, the same in every frame.
    if (n.multipath && n.multipathAlbedo > 0.f) {
        const cv::Mat1f bias_m =
            detail::multipathBias_m(raster.depth_m, raster.normals, k, n.multipathAlbedo);
        for (int y = 0; y < k.height_px; ++y)
            for (int x = 0; x < k.width_px; ++x)
                if (state.reading_m(y, x) > 0.f) state.reading_m(y, x) += bias_m(y, x);
    }

    // 9-11. Axial noise, quantisation, millimetres within the working range.
    const float axialFactor = n.axial ? n.scale * n.axialScale : 0.f;
    frame.depth_mm = cv::Mat1w::zeros(k.height_px, k.width_px);
    for (int y = 0; y < k.height_px; ++y)
        for (int x = 0; x < k.width_px; ++x) {
            float z_m = state.reading_m(y, x);
            if (z_m <= 0.f) continue;
            if (axialFactor > 0.f) {
                detail::PixelRng rng(seed, detail::NoiseStream::Axial,
                                     static_cast<std::uint64_t>(y) * k.width_px + x);
                z_m += axialFactor * n.axialSigma_m(z_m, state.incidence_rad(y, x)) *
                       static_cast<float>(rng.normal());
            }
            if (n.quantisation)
                z_m = detail::quantiseDepth_m(z_m, k.fx_px, n.baseline_m, n.subpixel);
            if (!(z_m >= n.minDepth_m && z_m <= n.maxDepth_m) || z_m <= 0.f) continue;
            frame.depth_mm(y, x) = static_cast<std::uint16_t>(
                std::min(std::lround(z_m * kMillimetresPerMetre), long{UINT16_MAX}));
        }
    return frame;
}

}  // namespace meadow::synth
