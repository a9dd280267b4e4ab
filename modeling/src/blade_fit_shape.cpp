// Nearest analytic blade shape of Jahrmann & Wimmer 2017 (Sec. 6.2) to a width profile.
#include <algorithm>
#include <cmath>

#include "meadow/modeling/blade_fit.h"

namespace meadow::modeling {
namespace {

// Triangle-tip tau is searched on this grid over [0, kMaxTau]; tau = 1 would be the quad.
constexpr float kTauStep = 0.01f;
constexpr float kMaxTau = 0.95f;

ShapeFit fitShape(AnalyticShape shape, float tau, const WidthProfile& profile) {
    const std::size_t n = profile.width_m.size();
    double ff = 0.0, fp = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const float v = static_cast<float>(i) / static_cast<float>(n - 1);
        const double f = analyticShapeWidthFraction(shape, v, tau);
        ff += f * f, fp += f * profile.width_m[i];
    }
    ShapeFit fit{
        .shape = shape, .baseWidth_m = ff > 0.0 ? static_cast<float>(fp / ff) : 0.f, .tau = tau};
    double err = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const float v = static_cast<float>(i) / static_cast<float>(n - 1);
        err += std::abs(fit.baseWidth_m * analyticShapeWidthFraction(shape, v, tau) -
                        profile.width_m[i]);
    }
    fit.error_m = static_cast<float>(err / static_cast<double>(n));
    return fit;
}

}  // namespace

float analyticShapeWidthFraction(AnalyticShape shape, float v, float tau) {
    v = std::clamp(v, 0.f, 1.f);
    switch (shape) {
        case AnalyticShape::Quad:
            return 1.f;
        case AnalyticShape::Triangle:
            return 1.f - v;
        case AnalyticShape::Quadratic:
        case AnalyticShape::OneSidedQuadratic:
            return 1.f - v * v;
        case AnalyticShape::TriangleTip:
            return v < tau ? 1.f : 1.f - (v - tau) / std::max(1.f - tau, 1e-6f);
    }
    return 1.f;
}

ShapeFit nearestAnalyticShape(const WidthProfile& profile) {
    if (profile.width_m.size() < 2) return {};
    ShapeFit best = fitShape(AnalyticShape::Quad, 0.5f, profile);
    for (AnalyticShape shape : {AnalyticShape::Triangle, AnalyticShape::Quadratic}) {
        const ShapeFit f = fitShape(shape, 0.5f, profile);
        if (f.error_m < best.error_m) best = f;
    }
    for (float tau = 0.f; tau <= kMaxTau + 1e-6f; tau += kTauStep) {
        const ShapeFit f = fitShape(AnalyticShape::TriangleTip, tau, profile);
        // Strictly better only: triangle-tip with tau = 0 is the triangle, which stays preferred.
        if (f.error_m < best.error_m - 1e-9f) best = f;
    }
    return best;
}

}  // namespace meadow::modeling
