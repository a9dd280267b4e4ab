#pragma once
// Synthetic blades and a storm for the physics tests (CPU reference and GPU): blades planted on a
// bumpy surface (up vectors up to ~50 degrees off +Y), each with a bent rest pose whose curve
// length is exactly its height, as the scene's seeding must produce it.
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <random>
#include <vector>

#include "physics_reference.h"

namespace meadow::runtime::testing {

struct TestMeadow {
    std::vector<gpu::BladeGpu> blades;
    std::vector<gpu::BladeRestGpu> rests;
};

inline TestMeadow makeTestMeadow(std::uint32_t count, std::uint32_t seed, float extent_m = 4.f) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.f, 1.f);
    TestMeadow m;
    for (std::uint32_t i = 0; i < count; ++i) {
        const glm::vec3 v0{extent_m * (unit(rng) - 0.5f), 0.2f * unit(rng),
                           extent_m * (unit(rng) - 0.5f)};
        const glm::vec3 up =
            glm::normalize(glm::vec3(1.2f * (unit(rng) - 0.5f), 1.f, 1.2f * (unit(rng) - 0.5f)));
        const float h = 0.2f + 0.4f * unit(rng);
        const float angle = 6.2831853f * unit(rng);
        const float s = 5.f + 10.f * unit(rng);
        const glm::vec3 f = shader::bladeFrontDirection(up, angle);
        const glm::vec3 tip = v0 + h * glm::normalize(up + 0.5f * unit(rng) * f);
        const glm::vec3 Iv1 =
            shader::middleControlPoint(v0, up, h, shader::projectedLength(v0, tip, up));
        const ValidatedCurve rest =
            validateBladeReference(v0, tip, up, h, Iv1, tip, PHYSICS_LENGTH_EXACT);
        m.blades.push_back({glm::vec4(v0, h), glm::vec4(rest.v1, 0.01f), glm::vec4(rest.v2, s),
                            glm::vec4(up, angle)});
        m.rests.push_back({glm::vec4(rest.v1, 0.f), glm::vec4(rest.v2, 0.f)});
    }
    return m;
}

// Strong wind: a travelling wave of up to 8 m/s, a 10 m/s point source, gusts and turbulence, under
// earth gravity.
inline PhysicsSettings stormSettings() {
    PhysicsSettings s;
    s.windDirection = glm::normalize(glm::vec3(1.f, 0.f, 0.3f));
    s.windWave_mps = 8.f;
    s.windSource_m = {0.5f, 0.f, -0.5f};
    s.windSource_mps = 10.f;
    s.windSourceRadius_m = 3.f;
    s.windGust_mps = 4.f;  // gusts and turbulence: the noise must agree on CPU and GPU too
    s.windGustSize_m = 1.5f;
    s.windTurbulence_mps = 2.f;
    s.windTurbulenceSize_m = 0.4f;
    return s;
}

inline PhysicsSettings calmSettings() {
    PhysicsSettings s;
    s.windWave_mps = 0.f;
    s.windSource_mps = 0.f;
    return s;
}

// Three spheres sweeping through the meadow on circles, at frame `frame` (60 Hz).
inline std::vector<CollisionSphere> sweepingSpheres(std::uint32_t frame) {
    const float t = static_cast<float>(frame) / 60.f;
    return {{{1.5f * std::cos(0.7f * t), 0.25f, 1.5f * std::sin(0.7f * t)}, 0.4f},
            {{-1.f + 0.8f * std::sin(1.3f * t), 0.1f, 0.6f * std::cos(1.1f * t)}, 0.6f},
            {{0.9f * std::sin(0.4f * t), 0.45f, -1.2f + 0.5f * std::cos(0.9f * t)}, 0.3f}};
}

}  // namespace meadow::runtime::testing
