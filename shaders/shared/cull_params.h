// Parameters of the per-blade culling pass (Jahrmann & Wimmer 2017, Sec. 5.2 / Eq. (14)-(15)),
// shared by shaders/cull.comp (a std140 uniform block) and the C++ CPU reference. Compiles as
// GLSL 4.50 and as C++20; mat4 / vec4 / uvec4 only, so std140 and the C++ layout agree.
#ifdef __cplusplus
#pragma once
#include <cstddef>
#include <glm/mat4x4.hpp>

#include "blade_types.h"
namespace meadow::runtime::gpu {
using mat4 = glm::mat4;
#endif

// Uniform buffer binding of CullParamsGpu, texture unit of the opaque depth pre-pass.
#define CULL_UBO_BINDING 2
#define CULL_DEPTH_TEXTURE_UNIT 0

// Bits of CullParamsGpu.counts.y: which tests run. Patch bounds count as frustum culling.
#define CULL_TEST_ORIENTATION 1u
#define CULL_TEST_FRUSTUM 2u
#define CULL_TEST_DISTANCE 4u
#define CULL_TEST_OCCLUSION 8u
#define CULL_TEST_ALL 15u

struct CullParamsGpu {
    mat4 clipFromWorld;       // OpenGL clip space, depth range [0, 1] after the divide + 0.5
    vec4 cameraPosition_m;    // xyz camera (world, m), w unused
    vec4 orientationFrustum;  // x Eq. (14) threshold on |dir_c . dir_b| (paper 0.9), y frustum
                              // tolerance (fraction of w, i.e. NDC units), zw unused
    vec4 distanceLevels;      // x d_max (m), y number of levels n (Eq. (15)), zw unused
    vec4 depthRange_m;        // x near (m), y far (m), z occlusion bias (m), w unused
    uvec4 counts;             // x patches, y CULL_TEST_* mask, z depth width (px), w height (px)
};

#ifdef __cplusplus
static_assert(sizeof(CullParamsGpu) == 144, "std140: a mat4 and five 16-byte rows");
static_assert(offsetof(CullParamsGpu, cameraPosition_m) == 64 &&
              offsetof(CullParamsGpu, counts) == 128);
}  // namespace meadow::runtime::gpu
#endif
