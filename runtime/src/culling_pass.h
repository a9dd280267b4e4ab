#pragma once
// The per-blade culling compute pass (shaders/cull.comp, Jahrmann & Wimmer 2017, Sec. 5.2): patch
// bounds, then orientation, frustum, distance and occlusion per blade. It owns what it writes:
// the visible-index buffer (uint per visible blade, read by the draw pass through gl_VertexID),
// the DrawArraysIndirect command (GL_PATCHES, one vertex per blade) and the per-test culled
// counts (CullStatsGpu).
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "gl/gl_object.h"
#include "gl/shader_program.h"
#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "shared/blade_types.h"

namespace meadow::runtime {

struct CullCamera {
    glm::mat4 clipFromWorld{1.f};
    glm::vec3 position_m{0.f};
    float near_m = 0.05f;
    float far_m = 200.f;
};

// The opaque depth pre-pass: a GL_DEPTH_COMPONENT* 2D texture (window depth in [0, 1]).
struct CullDepth {
    const gl::Texture& texture;
    std::uint32_t width_px;
    std::uint32_t height_px;
};

// Where a dispatch writes: the visible-index buffer (room for `capacity` uints), the
// DrawCommandGpu and the CullStatsGpu. The pass owns one set; a renderer may pass its own.
struct CullTargets {
    const gl::Buffer& visibleIndices;
    std::uint32_t capacity;
    const gl::Buffer& drawCommand;
    const gl::Buffer& stats;
};

class CullingPass {
public:
    // Compiles cull.comp and allocates room for bladeCapacity visible indices.
    CullingPass(GlContext& context, std::uint32_t bladeCapacity);

    // Resets the command and the stats, culls the blades of `patchCount` patches (PatchGpu[]) of
    // `blades` (bladeCount BladeGpu) and ends with the barriers for the indirect draw and
    // read-backs. depth == nullptr switches the occlusion test off. Throws std::invalid_argument
    // when bladeCount exceeds capacity().
    void dispatch(const gl::Buffer& blades, std::uint32_t bladeCount, const gl::Buffer& patches,
                  std::uint32_t patchCount, const CullCamera& camera, const CullSettings& settings,
                  const CullDepth* depth);
    // The same, writing into `targets` instead of the pass's own buffers.
    void dispatch(const gl::Buffer& blades, std::uint32_t bladeCount, const gl::Buffer& patches,
                  std::uint32_t patchCount, const CullCamera& camera, const CullSettings& settings,
                  const CullDepth* depth, const CullTargets& targets);

    [[nodiscard]] const gl::Buffer& visibleIndices() const { return visible_; }
    [[nodiscard]] const gl::Buffer& drawCommand() const { return command_; }  // DrawCommandGpu
    [[nodiscard]] const gl::Buffer& stats() const { return stats_; }          // CullStatsGpu
    [[nodiscard]] std::uint32_t capacity() const { return capacity_; }

    // Read-backs (they wait for the GPU): for tests, reports and benchmarks, not per frame.
    [[nodiscard]] gpu::DrawCommandGpu readDrawCommand() const;
    [[nodiscard]] gpu::CullStatsGpu readStats() const;

private:
    GlContext& context_;
    gl::ShaderProgram program_;
    gl::Buffer params_;
    gl::Buffer visible_;
    gl::Buffer command_;
    gl::Buffer stats_;
    std::uint32_t capacity_;
};

}  // namespace meadow::runtime
