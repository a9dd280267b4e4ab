#include "plant_scenery.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "meadow/core/random.h"
#include "meadow/synth/plant_views.h"

namespace meadow::synth::plant {
namespace {

constexpr int kPotSegments = 32;
constexpr float kFloorHalf_m = 3.f;
constexpr float kWallHeight_m = 3.f;

LabelledMesh quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, std::uint16_t label) {
    return {{a, b, c, d}, {{0u, 1u, 2u}, {0u, 2u, 3u}}, label};
}

// A truncated cone open at the top (the pot's wall) and a disc of soil just below its rim.
LabelledMesh pot(float radius_m, float height_m) {
    LabelledMesh m;
    m.label = kPotLabel;
    const float bottomRadius = 0.75f * radius_m, soil = -0.01f;
    for (int s = 0; s < kPotSegments; ++s) {
        const float a = 2.f * std::numbers::pi_v<float> * static_cast<float>(s) / kPotSegments;
        const glm::vec3 dir(std::cos(a), 0.f, std::sin(a));
        m.positions_m.push_back(dir * radius_m);  // rim, y = 0
        m.positions_m.push_back(dir * bottomRadius + glm::vec3(0.f, -height_m, 0.f));
        m.positions_m.push_back(dir * (0.97f * radius_m) + glm::vec3(0.f, soil, 0.f));
    }
    const auto centre = static_cast<unsigned>(m.positions_m.size());
    m.positions_m.emplace_back(0.f, soil, 0.f);
    for (int s = 0; s < kPotSegments; ++s) {
        const auto i = static_cast<unsigned>(3 * s),
                   j = static_cast<unsigned>(3 * ((s + 1) % kPotSegments));
        m.triangles.emplace_back(i, j, i + 1);
        m.triangles.emplace_back(j, j + 1, i + 1);
        m.triangles.emplace_back(centre, i + 2, j + 2);
    }
    return m;
}

}  // namespace

Scenery benchScenery(float plantHeight_m, float wallBehind_m, std::uint64_t seed) {
    Scenery s;
    s.potRadius_m = std::clamp(0.1f * plantHeight_m, 0.04f, 0.15f);
    s.potHeight_m = 1.2f * s.potRadius_m;
    const float floor = -s.potHeight_m;
    s.meshes.push_back(pot(s.potRadius_m, s.potHeight_m));
    s.meshes.push_back(quad(
        {-kFloorHalf_m, floor, -wallBehind_m}, {-kFloorHalf_m, floor, kFloorHalf_m},
        {kFloorHalf_m, floor, kFloorHalf_m}, {kFloorHalf_m, floor, -wallBehind_m}, kFloorLabel));
    s.meshes.push_back(quad({-kFloorHalf_m, floor, -wallBehind_m},
                            {kFloorHalf_m, floor, -wallBehind_m},
                            {kFloorHalf_m, floor + kWallHeight_m, -wallBehind_m},
                            {-kFloorHalf_m, floor + kWallHeight_m, -wallBehind_m}, kWallLabel));
    // Clutter: a box on each side behind the plant, or one, sized and placed by the seed.
    Rng rng(seed ^ 0xc1077e4u);
    const int boxes = rng.chance(0.5f) ? 2 : 1;
    for (int b = 0; b < boxes; ++b) {
        const float side = (b == 0) == rng.chance(0.5f) ? 1.f : -1.f;
        const glm::vec3 size(rng.uniform(0.12f, 0.3f), rng.uniform(0.1f, 0.45f),
                             rng.uniform(0.1f, 0.2f));
        const float x = side * rng.uniform(2.f * s.potRadius_m + 0.1f, 2.f * s.potRadius_m + 0.4f);
        const float z = -rng.uniform(0.45f, 0.85f) * wallBehind_m;
        s.meshes.push_back(boxMesh({x - 0.5f * size.x, floor, z - 0.5f * size.z},
                                   {x + 0.5f * size.x, floor + size.y, z + 0.5f * size.z},
                                   kClutterLabel));
    }
    return s;
}

}  // namespace meadow::synth::plant
