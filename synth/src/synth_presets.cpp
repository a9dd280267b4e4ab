// The synthetic tuft catalog: the five blade types of Fan & Sheng 2017, Fig. 10, and stress cases
// for capture (touching, asymmetric, curling, thin blades, a tilted camera, heavy noise, wind).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

#include "meadow/core/random.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::synth {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float deg(float degrees) { return degrees * kPi / 180.f; }

// Width profile samples: every 5 % of the length, so every breakpoint of the shapes below (all
// at multiples of 0.05) is a sample and the profile is exactly the shape.
constexpr int kProfileSamples = 21;
// Mesh segments: a multiple of the profile's 20 intervals reproduces it exactly, and at 1 cm or
// less per segment the ribbon follows the bend to well under a millimetre.
constexpr int kMeshSegments = 40;
// Bases of a tuft lie within this distance (m) of the tuft's centre: a common base.
constexpr float kBaseSpread_m = 0.006f;
// The camera looks at this fraction of the tallest blade's height above the ground.
constexpr float kTargetHeightFraction = 0.45f;

// Relative width (0..1 of the maximum) at arc-length fraction s, piecewise linear.
using WidthShape = float (*)(float s);

float lerpShape(float s, std::initializer_list<std::pair<float, float>> knots) {
    auto prev = *knots.begin();
    for (const auto& k : knots) {
        if (s <= k.first) {
            if (k.first <= prev.first) return k.second;
            const float f = (s - prev.first) / (k.first - prev.first);
            return prev.second + f * (k.second - prev.second);
        }
        prev = k;
    }
    return prev.second;
}

// Fig. 10 (a) slim grass: nearly constant width, tapering over the last quarter.
float slimShape(float s) { return lerpShape(s, {{0.f, 1.f}, {0.75f, 0.88f}, {1.f, 0.f}}); }
// Fig. 10 (b) quadratic edges: w = 4 u (1 - u) with u = 0.25 + 0.75 s, widest at a third.
float quadraticShape(float s) {
    const float u = 0.25f + 0.75f * s;
    return 4.f * u * (1.f - u);
}
// Fig. 10 (c) long shrub leaf: narrow stalk, widest at a quarter, long slow taper.
float shrubShape(float s) {
    return lerpShape(s, {{0.f, 0.45f}, {0.25f, 1.f}, {0.75f, 0.6f}, {1.f, 0.f}});
}
// Fig. 10 (d) bamboo leaf: flat (constant width) in the middle.
float bambooShape(float s) {
    return lerpShape(s, {{0.f, 0.4f}, {0.15f, 1.f}, {0.7f, 1.f}, {1.f, 0.f}});
}
// Fig. 10 (e) sharp narrow tip: full width to 80 %, then a fast taper into a long thin point.
float sharpTipShape(float s) {
    return lerpShape(s, {{0.f, 0.8f}, {0.1f, 1.f}, {0.8f, 1.f}, {0.9f, 0.2f}, {1.f, 0.f}});
}

struct BladeType {
    const char* name;
    WidthShape shape;
    AnalyticShape nearest;
    float tau;                               // triangle-tip start, where nearest is TriangleTip
    float minHeight_m, maxHeight_m;          // real-grass plausible
    float minWidth_m, maxWidth_m;            // maximum width of the blade
    float minTipAngle_rad, maxTipAngle_rad;  // how far the tip's tangent turns from the base's
};

const BladeType kSlim{
    "slim-grass", slimShape, AnalyticShape::TriangleTip, 0.75f, 0.20f, 0.35f, 0.002f, 0.005f,
    deg(25),      deg(60)};
const BladeType kQuadratic{
    "quadratic-leaf", quadraticShape, AnalyticShape::Quadratic, 0.5f, 0.12f, 0.20f, 0.012f, 0.020f,
    deg(20),          deg(45)};
const BladeType kShrub{
    "shrub-leaf", shrubShape, AnalyticShape::Quadratic, 0.5f, 0.22f, 0.35f, 0.008f, 0.014f,
    deg(25),      deg(55)};
const BladeType kBamboo{
    "bamboo-leaf", bambooShape, AnalyticShape::TriangleTip, 0.7f, 0.14f, 0.22f, 0.015f, 0.025f,
    deg(15),       deg(40)};
const BladeType kSharp{
    "sharp-tip", sharpTipShape, AnalyticShape::TriangleTip, 0.8f, 0.12f, 0.20f, 0.006f, 0.010f,
    deg(15),     deg(40)};

// An archetype of the given type: spine of arc length height_m from the origin up +Y, bending
// toward +X so that its tip tangent has turned by tipAngle; v1 on +Y (the base direction).
Archetype makeArchetype(const BladeType& type, float height_m, float maxWidth_m,
                        float tipAngle_rad) {
    Archetype a;
    a.name = type.name;
    a.nearestShape = type.nearest;
    a.tau = type.tau;
    // For a circular arc turning by Theta, the chord is L sin(Theta/2) / (Theta/2) and points
    // Theta/2 from the base tangent; a quadratic Bézier with that chord and length is close.
    const float half = 0.5f * tipAngle_rad;
    const float chord_m = height_m * std::sin(half) / half;
    const glm::vec3 v2 = chord_m * glm::vec3(std::sin(half), std::cos(half), 0.f);
    a.spine_m = spineWithLength(glm::vec3(0.f), glm::vec3(0.f, 1.f, 0.f), v2, height_m);
    a.width.width_m.resize(kProfileSamples);
    for (int i = 0; i < kProfileSamples; ++i) {
        const float s = static_cast<float>(i) / (kProfileSamples - 1);
        a.width.width_m[i] = maxWidth_m * type.shape(s);
    }
    return a;
}

Archetype randomArchetype(const BladeType& type, Rng& rng) {
    const float h = rng.uniform(type.minHeight_m, type.maxHeight_m);
    const float w = rng.uniform(type.minWidth_m, type.maxWidth_m);
    const float tip = rng.uniform(type.minTipAngle_rad, type.maxTipAngle_rad);
    return makeArchetype(type, h, w, tip);
}

// How the blades of a tuft fan out from their common base.
struct FanStyle {
    float halfFan_rad = deg(30);    // leans spread evenly over [-halfFan, +halfFan]
    float leanJitter_rad = deg(4);  // plus this much at random
    float yawJitter_rad = deg(20);  // face turned off square-on by up to this
    float inwardShare = 0.f;        // share of blades bending toward the middle (crossing)
};

// n blades from `pick` spread as a fan; blade i + 1 is the i-th from image left.
template <class Pick>
std::vector<BladePlacement> fan(int n, Rng& rng, const FanStyle& style, Pick pick) {
    std::vector<BladePlacement> blades;
    for (int i = 0; i < n; ++i) {
        BladePlacement b;
        b.archetype = pick(rng, i);
        b.mesh.segments = kMeshSegments;
        const float f = n == 1 ? 0.5f : static_cast<float>(i) / static_cast<float>(n - 1);
        b.lean_rad = style.halfFan_rad * (2.f * f - 1.f) +
                     rng.uniform(-style.leanJitter_rad, style.leanJitter_rad);
        b.yaw_rad = rng.uniform(-style.yawJitter_rad, style.yawJitter_rad);
        b.base_m = {rng.uniform(-kBaseSpread_m, kBaseSpread_m), 0.f,
                    rng.uniform(-kBaseSpread_m, kBaseSpread_m)};
        const bool outward = std::abs(b.lean_rad) < deg(2) ? rng.chance(0.5f) : b.lean_rad > 0.f;
        b.bendsTowardPlusX = rng.chance(style.inwardShare) ? !outward : outward;
        b.gustPhase_rad = rng.uniform(0.f, 2.f * kPi);
        blades.push_back(std::move(b));
    }
    return blades;
}

TuftSpec tuftAround(std::vector<BladePlacement> blades, const TuftParams& p) {
    TuftSpec spec;
    float tallest_m = 0.f;
    for (const BladePlacement& b : blades) tallest_m = std::max(tallest_m, b.archetype.height_m());
    spec.blades = std::move(blades);
    spec.camera.intrinsics = p.intrinsics;
    spec.camera.distance_m = p.distance_m;
    spec.camera.target_m = {0.f, kTargetHeightFraction * tallest_m, 0.f};
    return spec;
}

TuftSpec singleType(const BladeType& type, const TuftParams& p, const FanStyle& style = {}) {
    Rng rng(p.seed);
    return tuftAround(
        fan(p.bladeCount, rng, style, [&](Rng& r, int) { return randomArchetype(type, r); }), p);
}

std::vector<SynthPreset> makeCatalog() {
    std::vector<SynthPreset> c;
    const auto add = [&c](std::string name, std::string description, float distance_m, int blades,
                          std::function<TuftSpec(const TuftParams&)> build,
                          float noiseMultiplier = 1.f) {
        c.push_back({std::move(name), std::move(description), distance_m, blades, noiseMultiplier,
                     std::move(build)});
    };
    add("slim-grass", "Fan & Sheng Fig. 10: slim grass blades, 2-5 mm wide, 20-35 cm tall", 0.8f, 9,
        [](const TuftParams& p) { return singleType(kSlim, p); });
    add("quadratic-leaf", "Fan & Sheng Fig. 10: leaves with quadratic edges, 12-20 mm wide", 0.7f,
        5, [](const TuftParams& p) { return singleType(kQuadratic, p); });
    add("shrub-leaf", "Fan & Sheng Fig. 10: long shrub leaves, widest near the base, 22-35 cm",
        0.9f, 5, [](const TuftParams& p) { return singleType(kShrub, p); });
    add("bamboo-leaf", "Fan & Sheng Fig. 10: bamboo leaves, flat (constant width) in the middle",
        0.8f, 4, [](const TuftParams& p) { return singleType(kBamboo, p); });
    add("sharp-tip", "Fan & Sheng Fig. 10: blades ending in a sharp narrow tip", 0.7f, 6,
        [](const TuftParams& p) { return singleType(kSharp, p); });
    add("touching", "stress: wide leaves in a narrow fan, touching and crossing each other", 0.7f,
        6, [](const TuftParams& p) {
            FanStyle style;
            style.halfFan_rad = deg(12);
            style.inwardShare = 0.35f;
            Rng rng(p.seed);
            return tuftAround(
                fan(p.bladeCount, rng, style,
                    [](Rng& r, int i) { return randomArchetype(i % 2 ? kBamboo : kQuadratic, r); }),
                p);
        });
    add("asymmetric", "stress: leaves whose two sides of the spine differ in width (25/75 %)", 0.7f,
        4, [](const TuftParams& p) {
            TuftSpec spec = singleType(kBamboo, p);
            Rng rng(p.seed ^ 0xa5a5a5a5u);
            for (BladePlacement& b : spec.blades)
                b.archetype.leftWidthFraction =
                    rng.chance(0.5f) ? rng.uniform(0.22f, 0.32f) : rng.uniform(0.68f, 0.78f);
            return spec;
        });
    add("curl", "stress: long leaves curling out of their face plane toward the camera, twisted",
        0.8f, 4, [](const TuftParams& p) {
            TuftSpec spec = singleType(kShrub, p);
            Rng rng(p.seed ^ 0x5eedc0deu);
            for (std::size_t i = 0; i < spec.blades.size(); i += 2) {
                BladePlacement& b = spec.blades[i];
                b.curlTowardCamera_rad = rng.uniform(deg(40), deg(65));
                b.archetype.twistAtTip_rad =
                    (rng.chance(0.5f) ? 1.f : -1.f) * rng.uniform(deg(50), deg(90));
            }
            return spec;
        });
    add("thin", "stress: slim blades under 2 px wide at the camera distance", 1.0f, 8,
        [](const TuftParams& p) {
            BladeType thin = kSlim;
            // 1.2-1.8 px at the tuft's distance: below what the sensor resolves (< ~2 px).
            thin.minWidth_m = 1.2f * p.distance_m / p.intrinsics.fx_px;
            thin.maxWidth_m = 1.8f * p.distance_m / p.intrinsics.fx_px;
            thin.name = "thin-grass";
            return singleType(thin, p);
        });
    add("tilted", "stress: the camera 35 deg above horizontal looking down on the tuft", 0.9f, 6,
        [](const TuftParams& p) {
            Rng rng(p.seed);
            TuftSpec spec = tuftAround(
                fan(p.bladeCount, rng, {},
                    [](Rng& r, int i) { return randomArchetype(i % 2 ? kSlim : kSharp, r); }),
                p);
            spec.camera.tilt_rad = deg(35);
            return spec;
        });
    add(
        "noisy", "stress: quadratic leaves under 3x the sensor's nominal noise", 0.7f, 5,
        [](const TuftParams& p) { return singleType(kQuadratic, p); }, 3.f);
    add("wind", "stress: slim grass and shrub leaves swaying in gusting wind (truth per frame)",
        0.8f, 7, [](const TuftParams& p) {
            Rng rng(p.seed);
            TuftSpec spec = tuftAround(
                fan(p.bladeCount, rng, {},
                    [](Rng& r, int i) { return randomArchetype(i % 3 ? kSlim : kShrub, r); }),
                p);
            spec.wind.tipDisplacementPerHeight = 0.3f;
            spec.wind.gustFrequency_hz = 1.5f;
            return spec;
        });
    return c;
}

}  // namespace

const std::vector<SynthPreset>& synthPresets() {
    static const std::vector<SynthPreset> catalog = makeCatalog();
    return catalog;
}

const SynthPreset* findSynthPreset(std::string_view name) {
    for (const SynthPreset& p : synthPresets())
        if (p.name == name) return &p;
    return nullptr;
}

std::string synthPresetNames() {
    std::string names;
    for (const SynthPreset& p : synthPresets()) names += (names.empty() ? "" : ", ") + p.name;
    return names;
}

TuftSpec buildPresetSpec(const SynthPreset& preset, TuftParams params) {
    if (params.distance_m <= 0.f) params.distance_m = preset.distance_m;
    if (params.bladeCount <= 0) params.bladeCount = preset.bladeCount;
    if (!(params.distance_m >= kMinSynthDistance_m && params.distance_m <= kMaxSynthDistance_m))
        throw std::invalid_argument(
            "buildPresetSpec: distance must be in [" + std::to_string(kMinSynthDistance_m) + ", " +
            std::to_string(kMaxSynthDistance_m) + "] m, got " + std::to_string(params.distance_m));
    if (params.bladeCount < kMinSynthBlades || params.bladeCount > kMaxSynthBlades)
        throw std::invalid_argument(
            "buildPresetSpec: blade count must be in [" + std::to_string(kMinSynthBlades) + ", " +
            std::to_string(kMaxSynthBlades) + "], got " + std::to_string(params.bladeCount));
    return preset.build(params);
}

}  // namespace meadow::synth
