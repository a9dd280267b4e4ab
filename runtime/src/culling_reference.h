#pragma once
// CPU reference of the per-blade culling (Jahrmann & Wimmer 2017, Sec. 5.2): the oracle the GPU
// pass is tested against. culling_reference.cpp compiles shaders/common_culling.glsl itself as
// C++, so the tests are the same text on both sides; only the depth fetch and the compaction
// (ordered here, atomic on the GPU) differ.
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "meadow/runtime/culling.h"
#include "shared/cull_params.h"

namespace meadow::runtime {

// The opaque depth pre-pass as the shader sees it: window depth in [0, 1], row 0 at the bottom
// (OpenGL texture order), width * height values.
struct DepthImageView {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::span<const float> depth;
};

// Packs the settings and this frame's camera into cull.comp's uniform block. `depth` may be
// null: the occlusion test is then switched off.
[[nodiscard]] gpu::CullParamsGpu packCullParams(const CullSettings& settings,
                                                const glm::mat4& clipFromWorld,
                                                glm::vec3 cameraPosition_m, float near_m,
                                                float far_m, std::uint32_t patchCount,
                                                std::uint32_t depthWidth,
                                                std::uint32_t depthHeight);

struct CullResult {
    std::vector<std::uint32_t> visible;  // blade indices, in patch order then blade order
    gpu::CullStatsGpu stats{};
};

// Culls every blade of every patch exactly as cull.comp does. Throws std::invalid_argument when a
// patch range leaves `blades`, or occlusion is on without a matching depth image.
[[nodiscard]] CullResult cullReference(std::span<const gpu::BladeGpu> blades,
                                       std::span<const gpu::PatchGpu> patches,
                                       const gpu::CullParamsGpu& params,
                                       const DepthImageView* depth);

}  // namespace meadow::runtime
