#pragma once
// CPU reference of the per-blade physics (Jahrmann & Wimmer 2017, Sec. 5): the oracle the GPU
// pass is tested against. The equations are not re-typed here: physics_reference.cpp compiles
// shaders/common_physics.glsl itself as C++ (glm in scope), so CPU and GPU run one text.
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "meadow/runtime/physics.h"
#include "shared/physics_params.h"

namespace meadow::runtime {

// Packs the user's settings and this frame's step into the uniform block of physics.comp.
[[nodiscard]] gpu::PhysicsParamsGpu packPhysicsParams(const PhysicsSettings& settings, float dt_s,
                                                      float time_s, std::uint32_t bladeCount,
                                                      std::uint32_t colliderCount);
[[nodiscard]] std::vector<gpu::ColliderGpu> packColliders(std::span<const CollisionSphere> spheres);

// One physics step on params.counts.x blades, exactly as physics.comp's main() runs it. Throws
// std::invalid_argument when the spans are shorter than the counts in `params`.
void physicsStepReference(std::span<gpu::BladeGpu> blades, std::span<gpu::BladeRestGpu> rests,
                          std::span<const gpu::ColliderGpu> colliders,
                          const gpu::PhysicsParamsGpu& params);

// A few functions of common_physics.glsl, declared for tests (defined by the shared text).
namespace shader {
float bezierArcLength(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2);
float bezierLengthPaper(glm::vec3 v0, glm::vec3 v1, glm::vec3 v2);
float projectedLength(glm::vec3 v0, glm::vec3 v2, glm::vec3 up);
glm::vec3 middleControlPoint(glm::vec3 v0, glm::vec3 up, float h, float lproj);
glm::vec3 tipAboveGround(glm::vec3 v0, glm::vec3 v2, glm::vec3 up);
glm::vec3 bladeWidthAxis(glm::vec3 up, float angle);
glm::vec3 bladeFrontDirection(glm::vec3 up, float angle);
glm::vec3 sphereCollisionTranslation(glm::vec3 p, glm::vec4 sphere);
glm::vec3 windInfluence(gpu::PhysicsParamsGpu p, glm::vec3 v0);
float valueNoise(glm::vec2 q, std::uint32_t salt);
}  // namespace shader

// validateBlade() of common_physics.glsl (Eq. (10)-(13)): the validated v1 and v2.
struct ValidatedCurve {
    glm::vec3 v1;
    glm::vec3 v2;
};
[[nodiscard]] ValidatedCurve validateBladeReference(glm::vec3 v0, glm::vec3 v2, glm::vec3 up,
                                                    float h, glm::vec3 Iv1, glm::vec3 Iv2,
                                                    unsigned lengthModel);

}  // namespace meadow::runtime
