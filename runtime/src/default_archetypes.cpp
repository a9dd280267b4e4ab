#include "default_archetypes.h"

#include <cmath>

namespace meadow::runtime {
namespace {

using modeling::AnalyticShape;
using modeling::Archetype;

// Profile samples along the blade; enough to show a rounded tip.
constexpr int kProfileSamples = 9;

// Full width (m) at arc-length fractions i / (n - 1): constant to `taperStart`, then narrowing to
// the tip with the given exponent (1 = straight taper, < 1 = rounded tip).
modeling::WidthProfile taperedProfile(float baseWidth_m, float taperStart, float exponent) {
    modeling::WidthProfile p;
    for (int i = 0; i < kProfileSamples; ++i) {
        const float s = static_cast<float>(i) / (kProfileSamples - 1);
        const float taper = s <= taperStart ? 1.f : 1.f - (s - taperStart) / (1.f - taperStart);
        p.width_m.push_back(baseWidth_m * std::pow(std::max(taper, 0.f), exponent));
    }
    return p;
}

Archetype make(const char* name, glm::vec3 v1, glm::vec3 v2, float width_m, AnalyticShape shape,
               float taperStart, float exponent) {
    Archetype a;
    a.name = name;
    a.spine_m = {glm::vec3(0.f), v1, v2};
    a.width = taperedProfile(width_m, taperStart, exponent);
    a.nearestShape = shape;
    a.tau = taperStart;
    return a;
}

}  // namespace

// Blade-local frame of archetype.h: +Y up, the in-face bend toward +X. Heights 0.2-0.4 m and
// widths 5-9 mm, the range of meadow grasses (Festuca, Lolium, Poa).
std::vector<Archetype> defaultArchetypes() {
    return {
        make("default-upright", {0.005f, 0.18f, 0.f}, {0.03f, 0.34f, 0.f}, 0.006f,
             AnalyticShape::Quadratic, 0.6f, 0.7f),
        make("default-arched", {0.02f, 0.2f, 0.f}, {0.15f, 0.28f, 0.f}, 0.008f,
             AnalyticShape::TriangleTip, 0.7f, 1.f),
        make("default-short", {0.01f, 0.11f, 0.f}, {0.04f, 0.2f, 0.f}, 0.005f,
             AnalyticShape::Triangle, 0.f, 1.f),
        make("default-broad", {0.015f, 0.16f, 0.f}, {0.08f, 0.3f, 0.f}, 0.009f, AnalyticShape::Quad,
             0.8f, 0.5f),
    };
}

}  // namespace meadow::runtime
