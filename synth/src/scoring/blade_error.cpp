#include "meadow/synth/blade_error.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <utility>
#include <vector>

#include "meadow/modeling/hausdorff.h"

namespace meadow::synth {
namespace {

using modeling::BladeFit;
using modeling::QuadraticBezier;

constexpr int kTruthSpineSamples = 400;  // dense truth spine for distances
constexpr int kWidthComparisonSamples = 50;
constexpr float kMillimetresPerMetre = 1000.f;

}  // namespace

BladeError bladeError(const BladeFit& fit, const SyntheticBlade& truth) {
    const QuadraticBezier spine = truth.spineInCamera_m();
    const float trueHeight_m = spine.length();
    std::vector<glm::vec3> dense(kTruthSpineSamples + 1);
    std::vector<float> denseS(kTruthSpineSamples + 1);
    for (int i = 0; i <= kTruthSpineSamples; ++i) {
        const float t = static_cast<float>(i) / kTruthSpineSamples;
        dense[static_cast<std::size_t>(i)] = spine.at(t);
        denseS[static_cast<std::size_t>(i)] = spine.lengthTo(t) / trueHeight_m;
    }
    const auto nearest = [&](const glm::vec3& p) {  // (arc fraction, distance m)
        float bestD = std::numeric_limits<float>::max(), bestS = 0.f;
        for (std::size_t i = 0; i < dense.size(); ++i)
            if (const float d = glm::distance(p, dense[i]); d < bestD) bestD = d, bestS = denseS[i];
        return std::pair<float, float>{bestS, bestD};
    };
    BladeError e;
    const QuadraticBezier& f = fit.spineCamera_m;
    e.v0_mm = glm::distance(f.v0, spine.v0) * kMillimetresPerMetre;
    e.v1_mm = glm::distance(f.v1, spine.v1) * kMillimetresPerMetre;
    e.v2_mm = glm::distance(f.v2, spine.v2) * kMillimetresPerMetre;
    e.heightError = (fit.archetype.height_m() - trueHeight_m) / trueHeight_m;
    double widthSum_m = 0.0;
    for (int i = 0; i <= kWidthComparisonSamples; ++i) {
        const float s = static_cast<float>(i) / kWidthComparisonSamples;
        widthSum_m += std::abs(fit.archetype.width.at(s) - truth.archetype.width.at(s));
    }
    e.widthMaeFraction = static_cast<float>(widthSum_m / (kWidthComparisonSamples + 1) /
                                            truth.archetype.width.maxWidth_m());
    for (int i = 0; i <= kWidthComparisonSamples; ++i)
        e.offCurve_mm = std::max(
            e.offCurve_mm, nearest(f.at(static_cast<float>(i) / kWidthComparisonSamples)).second *
                               kMillimetresPerMetre);
    if (fit.archetype.knots_m.size() >= 2) {
        std::vector<glm::vec3> knots;
        for (const glm::vec3& k : fit.archetype.knots_m) knots.push_back(fit.frame.toCamera(k));
        e.knotPolyline_mm = modeling::directedHausdorff_m(knots, dense) * kMillimetresPerMetre;
    }
    e.baseS = nearest(f.v0).first;
    e.tipS = nearest(f.v2).first;
    return e;
}

}  // namespace meadow::synth
