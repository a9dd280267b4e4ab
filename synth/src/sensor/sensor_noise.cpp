#include "sensor_noise.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace meadow::synth {
namespace {

// Nguyen, Izadi & Lovell 2012, Eq. 5: sigma_z(z) = a + b (z - z0)^2 m for 10 <= theta <= 60 deg.
constexpr float kAxialBase_m = 0.0012f;
constexpr float kAxialQuadratic_per_m = 0.0019f;  // m / m^2
constexpr float kAxialVertexDepth_m = 0.4f;
// Same equation, theta > 60 deg: + c / sqrt(z) * theta^2 / (pi/2 - theta)^2.
constexpr float kGrazingOnset_rad = std::numbers::pi_v<float> / 3.f;  // 60 deg
constexpr float kGrazingCoefficient_m = 0.0001f;                      // m * sqrt(m)
// The grazing term diverges at 90 deg and the paper measured no further than ~80 deg; beyond
// 85 deg it is held at its 85 deg value (~0.36 m at 1 m) so sigma stays finite.
constexpr float kGrazingModelLimit_rad = 85.f * std::numbers::pi_v<float> / 180.f;

// Largest depth a millimetre uint16 image can hold.
constexpr float kMaxRepresentableDepth_m = 65.535f;
constexpr float kUnbounded = std::numeric_limits<float>::infinity();

}  // namespace

float axialSigma_m(float z_m, float incidence_rad) {
    const float dz_m = z_m - kAxialVertexDepth_m;
    float sigma_m = kAxialBase_m + kAxialQuadratic_per_m * dz_m * dz_m;
    if (incidence_rad > kGrazingOnset_rad && z_m > 0.f) {
        const float theta = std::min(incidence_rad, kGrazingModelLimit_rad);
        const float toGrazing = std::numbers::pi_v<float> / 2.f - theta;
        sigma_m += kGrazingCoefficient_m / std::sqrt(z_m) * theta * theta / (toGrazing * toGrazing);
    }
    return sigma_m;
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
        {"lateral_px", lateral_px, 0.f, kUnbounded},
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
