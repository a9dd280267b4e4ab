// Buffer layouts, bindings and constants shared by the GLSL passes and the C++ runtime (and its
// CPU reference). Compiles as GLSL 4.50 (the loader prepends it) and as C++20.
// Only vec4 and scalars: glm::vec3 is 12 bytes while std430 aligns vec3 to 16.
#ifdef __cplusplus
#pragma once
#include <cstddef>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace meadow::runtime::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using uint = std::uint32_t;
using mat4 = glm::mat4;
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
#define DRAW_CHUNK_SSBO_BINDING 8  // draw pass only: the chunked draw commands

// Texture units of the draw pass (the culling pass's depth is unit 0, the terrain's 1 and 2).
#define FAR_FIELD_TEXTURE_UNIT 5
#define SHADOW_TEXTURE_UNIT 6

// Shadow cascades: the near one over shadows.distance_m of the view, the far one over four
// times that; side by side in one shadow-map texture.
#define SHADOW_CASCADES 2
#define SHADOW_FAR_CASCADE_SCALE 4.0

// Blades per indirect draw command (the draw pass splits the culling output into such chunks).
#define BLADE_DRAW_CHUNK 512

// Uniform buffer binding points.
#define FRAME_UBO_BINDING 0

// Analytic blade shapes of Jahrmann & Wimmer 2017, Sec. 6.2, in modeling::AnalyticShape's order.
#define BLADE_SHAPE_QUAD 0
#define BLADE_SHAPE_TRIANGLE 1
#define BLADE_SHAPE_QUADRATIC 2
#define BLADE_SHAPE_TRIANGLE_TIP 3
#define BLADE_SHAPE_ONE_SIDED_QUADRATIC 4

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
// 1 = widest), the nearest analytic shape for the tessellation fallback, and how the width sits
// about the spine.
struct ArchetypeGpu {
    vec4 widthProfile[ARCHETYPE_WIDTH_SAMPLES / 4];
    vec4 shape;  // x analytic shape id (BLADE_SHAPE_*), y tau (triangle-tip), z 1 = draw with
                 // widthProfile, 0 = with the analytic shape, w unused
    vec4 sides;  // x share of the width left of the spine (0.5 symmetric), y twist at the tip
                 // about the spine (rad), zw unused
};

// glDrawArraysIndirect's command: the culling pass writes vertexCount (one patch vertex per
// visible blade); the draw pass reads it from GL_DRAW_INDIRECT_BUFFER.
struct DrawCommandGpu {
    uint vertexCount;
    uint instanceCount;
    uint firstVertex;
    uint baseInstance;
};

// Blades removed by each culling test this frame (Jahrmann & Wimmer 2017, Sec. 5).
struct CullStatsGpu {
    uint culledOrientation;
    uint culledFrustum;
    uint culledDistance;
    uint culledOcclusion;
};

// An equal-size patch of blades (Sec. 4): contiguous blade indices and a world-space box that
// contains every pose its blades can reach (v0 +- the blade height in every direction).
struct PatchGpu {
    vec4 boundsMin_m;  // xyz world, w unused
    vec4 boundsMax_m;  // xyz world, w unused
    uvec4 range;       // x first blade, y blade count, zw unused
};

// A sphere that pushes blades (Sec. 5.1, collision).
struct ColliderGpu {
    vec4 center_radius_m;  // xyz world centre (m), w radius (m)
};

// Per-frame values every pass may read (std140 and std430 agree on mat4/vec4).
struct FrameGpu {
    mat4 viewFromWorld;
    mat4 clipFromWorld;
    vec4 cameraPosition_time;  // xyz camera position (world, m), w time (s)
    vec4 lightDirection;       // xyz unit direction toward the light (world), w intensity
    vec4 viewport_px;          // xy framebuffer size (px), z near (m), w far (m)
    vec4 wind;                 // xyz wind direction (unit, world), w wave amplitude (m/s)
    mat4 worldFromClip;        // inverse of clipFromWorld: the sky's view rays
    mat4 lightClipFromWorld[SHADOW_CASCADES];  // each shadow cascade's projection (shadows)
    vec4 horizon;  // xyz linear sky colour at the horizon, w fog distance (m), 0 none
    vec4 zenith;   // xyz linear sky colour straight up, w shadow strength (0: none)
};

#ifdef __cplusplus
static_assert(sizeof(BladeGpu) == 64 && offsetof(BladeGpu, up_direction) == 48);
static_assert(sizeof(BladeRestGpu) == 32);
static_assert(sizeof(ArchetypeGpu) == 96);
static_assert(sizeof(DrawCommandGpu) == 16 && sizeof(CullStatsGpu) == 16);
static_assert(sizeof(PatchGpu) == 48 && sizeof(ColliderGpu) == 16);
static_assert(sizeof(FrameGpu) == 416 && offsetof(FrameGpu, cameraPosition_time) == 128 &&
              offsetof(FrameGpu, horizon) == 384);
}  // namespace meadow::runtime::gpu
#endif
