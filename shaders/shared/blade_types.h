// Buffer layouts, bindings and constants shared by the GLSL passes and the C++ runtime (and its
// CPU reference). Compiles as GLSL 4.50 (the loader prepends it) and as C++20.
// Only vec4 and scalars: glm::vec3 is 12 bytes while std430 aligns vec3 to 16.
#ifdef __cplusplus
#pragma once
#include <cstddef>
#include <cstdint>
#include <glm/vec4.hpp>
namespace meadow::runtime::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using uint = std::uint32_t;
#endif

#define BLADE_WORKGROUP_SIZE 64

// Shader storage buffer binding points.
#define BLADE_SSBO_BINDING 0
#define BLADE_REST_SSBO_BINDING 1
#define ARCHETYPE_SSBO_BINDING 2
#define VISIBLE_INDEX_SSBO_BINDING 3
#define DRAW_COMMAND_SSBO_BINDING 4
#define CULL_STATS_SSBO_BINDING 5
#define PATCH_SSBO_BINDING 6
#define COLLIDER_SSBO_BINDING 7

// Samples of an archetype's width profile over normalised length (t = i / (N - 1)).
#define ARCHETYPE_WIDTH_SAMPLES 16

// One blade, Jahrmann & Wimmer 2017, Sec. 3: four vec4s (64 bytes).
struct BladeGpu {
    vec4 v0_height;     // xyz root (world, m), w height h (m)
    vec4 v1_width;      // xyz middle control point (world, m), w width (m)
    vec4 v2_stiffness;  // xyz tip (world, m), w stiffness s
    vec4 up_direction;  // xyz up (unit, world), w direction angle (rad)
};

// Per-blade state that the draw pass does not need: the captured rest pose that recovery pulls
// toward, the persistent collision strength eta, and the archetype index.
struct BladeRestGpu {
    vec4 restV1_archetype;  // xyz rest middle control point (world, m), w archetype index
    vec4 restV2_eta;        // xyz rest tip (world, m), w collision strength eta
};

// One archetype as the renderer uses it: the width profile (relative to the blade's width,
// 1 = widest) and the nearest analytic shape for the tessellation fallback.
struct ArchetypeGpu {
    vec4 widthProfile[ARCHETYPE_WIDTH_SAMPLES / 4];
    vec4 shape;  // x analytic shape id, y tau (triangle-tip), z unused, w unused
};

#ifdef __cplusplus
static_assert(sizeof(BladeGpu) == 64 && offsetof(BladeGpu, up_direction) == 48);
static_assert(sizeof(BladeRestGpu) == 32);
static_assert(sizeof(ArchetypeGpu) == 80);
}  // namespace meadow::runtime::gpu
#endif
