#include "physics_reference.h"

#include <glm/glm.hpp>
#include <stdexcept>
#include <string>

namespace meadow::runtime {

// The shared GLSL, compiled as C++: glm provides vec3/vec4 and the GLSL built-ins.
namespace shader {
using namespace glm;
using gpu::BladeGpu;
using gpu::BladeRestGpu;
using gpu::PhysicsParamsGpu;
#include "common_physics.glsl"
}  // namespace shader

ValidatedCurve validateBladeReference(glm::vec3 v0, glm::vec3 v2, glm::vec3 up, float h,
                                      glm::vec3 Iv1, glm::vec3 Iv2, unsigned lengthModel) {
    const shader::BladeCurve c = shader::validateBlade(v0, v2, up, h, Iv1, Iv2, lengthModel);
    return {c.v1, c.v2};
}

gpu::PhysicsParamsGpu packPhysicsParams(const PhysicsSettings& s, float dt_s, float time_s,
                                        std::uint32_t bladeCount, std::uint32_t colliderCount) {
    gpu::PhysicsParamsGpu p{};
    p.gravityDirection = glm::vec4(s.gravityDirection, s.gravity_mps2);
    p.gravityCenter = glm::vec4(s.gravityCenter_m, s.gravityCenter_mps2);
    p.gravityMix_dt = glm::vec4(s.mass, s.gravityCenterMix, dt_s, time_s);
    p.windWave = glm::vec4(s.windDirection, s.windWave_mps);
    p.windSource = glm::vec4(s.windSource_m, s.windSource_mps);
    p.windShape = glm::vec4(s.windWavelength_m, s.windFrequency_hz, s.windSourceRadius_m,
                            s.windGustSpeed_mps);
    p.windGust =
        glm::vec4(s.windGust_mps, s.windGustSize_m, s.windTurbulence_mps, s.windTurbulenceSize_m);
    p.collision = glm::vec4(s.etaDecay_per_s, s.recoveryFloor, s.etaGain, 0.f);
    p.counts = glm::uvec4(bladeCount, colliderCount,
                          s.exactLength ? PHYSICS_LENGTH_EXACT : PHYSICS_LENGTH_PAPER, 0u);
    return p;
}

std::vector<gpu::ColliderGpu> packColliders(std::span<const CollisionSphere> spheres) {
    std::vector<gpu::ColliderGpu> out;
    out.reserve(spheres.size());
    for (const CollisionSphere& s : spheres) out.push_back({glm::vec4(s.center_m, s.radius_m)});
    return out;
}

void physicsStepReference(std::span<gpu::BladeGpu> blades, std::span<gpu::BladeRestGpu> rests,
                          std::span<const gpu::ColliderGpu> colliders,
                          const gpu::PhysicsParamsGpu& params) {
    if (blades.size() < params.counts.x || rests.size() < params.counts.x ||
        colliders.size() < params.counts.y)
        throw std::invalid_argument(
            "physicsStepReference: " + std::to_string(blades.size()) + " blades, " +
            std::to_string(rests.size()) + " rest poses, " + std::to_string(colliders.size()) +
            " colliders, but params.counts asks for " + std::to_string(params.counts.x) +
            " blades and " + std::to_string(params.counts.y) + " colliders");
    using namespace shader;
    // Mirrors main() of shaders/physics.comp line for line.
    for (std::uint32_t i = 0; i < params.counts.x; ++i) {
        const BladeGpu blade = blades[i];
        const BladeRestGpu rest = rests[i];
        const vec3 v0 = vec3(blade.v0_height);
        const vec3 v1 = vec3(blade.v1_width);
        const vec3 up = vec3(blade.up_direction);
        const float h = blade.v0_height.w;

        vec3 v2 = forcedTip(blade, rest, params);

        vec3 d = vec3(0.0f);
        for (std::uint32_t k = 0; k < params.counts.y; ++k)
            d += bladeSphereTranslation(v0, v1, v2, colliders[k].center_radius_m);
        v2 += d;
        const float eta = collisionStrength(rest.restV2_eta.w, d, h, params.collision.x,
                                            params.collision.z, params.gravityMix_dt.z);

        const BladeCurve curve = validateBlade(v0, v2, up, h, vec3(rest.restV1_archetype),
                                               vec3(rest.restV2_eta), params.counts.z);
        blades[i].v1_width = vec4(curve.v1, blade.v1_width.w);
        blades[i].v2_stiffness = vec4(curve.v2, blade.v2_stiffness.w);
        rests[i].restV2_eta.w = eta;
    }
}

}  // namespace meadow::runtime
