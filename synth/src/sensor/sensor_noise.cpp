#include "sensor_noise.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace meadow::synth {
namespace {

// Nguyen, Izadi & Lovell 2012, Eq. 5, grazing term: it applies beyond 60 deg.
constexpr float kGrazingOnset_rad = std::numbers::pi_v<float> / 3.f;
// The grazing term diverges at 90 deg and the paper measured no further than ~80 deg; beyond
// 85 deg it is held at its 85 deg value (~0.36 m at 1 m) so sigma stays finite.
constexpr float kGrazingModelLimit_rad = 85.f * std::numbers::pi_v<float> / 180.f;

// Bounds that keep the image-wide terms' windows and powers within reason: a correlation or a
// fattening wider than this is a blurred image, not a sensor, and depth powers beyond this
// overflow a float over the working range.
constexpr float kMaxCorrelation_px = 64.f;
constexpr float kMaxEdgeFattening_px = 32.f;
constexpr float kMaxGrazingDepthPower = 4.f;
// Largest depth a millimetre uint16 image can hold.
constexpr float kMaxRepresentableDepth_m = 65.535f;
constexpr float kUnbounded = std::numeric_limits<float>::infinity();

}  // namespace

float NoiseModel::axialSigma_m(float z_m, float incidence_rad) const {
    const float dz_m = z_m - axialVertex_m;
    float sigma_m = axialBase_m + axialQuadratic_per_m * dz_m * dz_m;
    if (incidence_rad > kGrazingOnset_rad && z_m > 0.f) {
        const float theta = std::min(incidence_rad, kGrazingModelLimit_rad);
        const float toGrazing = std::numbers::pi_v<float> / 2.f - theta;
        // z^p written as z^(p + 1/2) / sqrt(z): Nguyen's p = -1/2 then divides by sqrt(z) alone,
        // exactly as their equation reads.
        const float depthFactor = std::pow(z_m, axialGrazingDepthPower + 0.5f);
        sigma_m +=
            axialGrazing_m * depthFactor / std::sqrt(z_m) * theta * theta / (toGrazing * toGrazing);
    }
    return sigma_m;
}

float axialSigma_m(float z_m, float incidence_rad) {
    return NoiseModel{}.axialSigma_m(z_m, incidence_rad);
}

float disparityStep_m(float z_m, float fx_px, float baseline_m, float subpixel) {
    return z_m * z_m / (subpixel * fx_px * baseline_m);
}

NoiseModel NoiseModel::none() {
    NoiseModel m;
    m.axial = false;
    m.lateral = false;
    m.quantisation = false;
    m.shadows = false;
    m.grazingDropout = false;
    m.flyingPixels = false;
    m.edgeFattening = false;
    m.multipath = false;
    m.scale = 0.f;
    m.minDepth_m = 0.f;
    m.maxDepth_m = kMaxRepresentableDepth_m;
    return m;
}

std::string NoiseModel::problem() const {
    const struct {
        const char* name;
        float value;
        float min;
        float max;
    } fields[] = {
        {"axialScale", axialScale, 0.f, kUnbounded},
        {"axialBase_m", axialBase_m, 0.f, kUnbounded},
        {"axialQuadratic_per_m", axialQuadratic_per_m, 0.f, kUnbounded},
        {"axialVertex_m", axialVertex_m, 0.f, kMaxRepresentableDepth_m},
        {"axialGrazing_m", axialGrazing_m, 0.f, kUnbounded},
        {"axialGrazingDepthPower", axialGrazingDepthPower, -kMaxGrazingDepthPower,
         kMaxGrazingDepthPower},
        {"lateral_px", lateral_px, 0.f, kUnbounded},
        {"lateralCorrelation_px", lateralCorrelation_px, 0.f, kMaxCorrelation_px},
        {"edgeFattening_px", edgeFattening_px, 0.f, kMaxEdgeFattening_px},
        {"multipathAlbedo", multipathAlbedo, 0.f, 1.f},
        {"baseline_m", baseline_m, 0.f, kUnbounded},
        {"subpixel", subpixel, 0.f, kUnbounded},
        {"maxIncidence_deg", maxIncidence_deg, 0.f, 90.f},
        {"flyingPixelRate", flyingPixelRate, 0.f, 1.f},
        {"scale", scale, 0.f, kUnbounded},
        {"minDepth_m", minDepth_m, 0.f, kMaxRepresentableDepth_m},
        {"maxDepth_m", maxDepth_m, 0.f, kMaxRepresentableDepth_m},
    };
    for (const auto& f : fields) {
        if (std::isnan(f.value) || f.value < f.min || f.value > f.max || std::isinf(f.value))
            return std::string("NoiseModel::") + f.name + " must be in [" + std::to_string(f.min) +
                   ", " + (std::isinf(f.max) ? "inf" : std::to_string(f.max)) + "], got " +
                   std::to_string(f.value);
    }
    // Division by these: a zero baseline or subpixel count has no disparity to quantise.
    if ((quantisation || shadows) && baseline_m <= 0.f)
        return "NoiseModel::baseline_m must be positive with quantisation or shadows on";
    if (quantisation && subpixel <= 0.f)
        return "NoiseModel::subpixel must be positive with quantisation on";
    if (minDepth_m >= maxDepth_m)
        return "NoiseModel::minDepth_m (" + std::to_string(minDepth_m) +
               ") must be below maxDepth_m (" + std::to_string(maxDepth_m) + ")";
    return {};
}

namespace detail {

float incidenceAngle_rad(const cv::Vec3f& normal, float u_px, float v_px, const Intrinsics& k) {
    const cv::Vec3f ray{(u_px - k.cx_px) / k.fx_px, (v_px - k.cy_px) / k.fy_px, 1.f};
    const float cosTheta = std::abs(normal.dot(ray)) / static_cast<float>(cv::norm(ray));
    return std::acos(std::clamp(cosTheta, 0.f, 1.f));
}

float quantiseDepth_m(float z_m, float fx_px, float baseline_m, float subpixel) {
    const double fb = static_cast<double>(fx_px) * baseline_m;
    const double steps = std::round(fb / z_m * subpixel);
    if (steps <= 0.0) return 0.f;
    return static_cast<float>(fb * subpixel / steps);
}

}  // namespace detail
}  // namespace meadow::synth
