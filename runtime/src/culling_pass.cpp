#include "culling_pass.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "culling_reference.h"
#include "gl/dispatch.h"

namespace meadow::runtime {

namespace {
gl::ProgramSource cullProgramSource() {
    return {
        .label = "blade culling",
        .stages = {{GL_COMPUTE_SHADER, "cull.comp"}},
        .commonFiles = {"shared/physics_params.h", "shared/cull_params.h", "common_dispatch.glsl",
                        "common_physics.glsl", "common_culling.glsl", "common_culling_depth.glsl"},
        .defines = {}};
}
}  // namespace

CullingPass::CullingPass(GlContext& context, std::uint32_t bladeCapacity)
    : context_(context),
      program_(cullProgramSource()),
      params_(gl::Buffer::create()),
      visible_(gl::Buffer::create()),
      command_(gl::Buffer::create()),
      stats_(gl::Buffer::create()),
      capacity_(std::max<std::uint32_t>(bladeCapacity, 1)) {
    glNamedBufferStorage(params_.id(), sizeof(gpu::CullParamsGpu), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(visible_.id(), std::size_t{capacity_} * sizeof(std::uint32_t), nullptr, 0);
    const gpu::DrawCommandGpu empty{0u, 1u, 0u, 0u};
    glNamedBufferStorage(command_.id(), sizeof(empty), &empty, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(stats_.id(), sizeof(gpu::CullStatsGpu), nullptr, GL_DYNAMIC_STORAGE_BIT);
    context_.checkErrors("CullingPass: creating buffers");
}

void CullingPass::dispatch(const gl::Buffer& blades, std::uint32_t bladeCount,
                           const gl::Buffer& patches, std::uint32_t patchCount,
                           const CullCamera& camera, const CullSettings& settings,
                           const CullDepth* depth) {
    dispatch(blades, bladeCount, patches, patchCount, camera, settings, depth,
             CullTargets{visible_, capacity_, command_, stats_});
}

void CullingPass::dispatch(const gl::Buffer& blades, std::uint32_t bladeCount,
                           const gl::Buffer& patches, std::uint32_t patchCount,
                           const CullCamera& camera, const CullSettings& settings,
                           const CullDepth* depth, const CullTargets& targets) {
    if (bladeCount > targets.capacity)
        throw std::invalid_argument("CullingPass::dispatch: " + std::to_string(bladeCount) +
                                    " blades, but the visible-index buffer holds " +
                                    std::to_string(targets.capacity));
    const gpu::CullParamsGpu params = packCullParams(
        settings, camera.clipFromWorld, camera.position_m, camera.near_m, camera.far_m, patchCount,
        depth ? depth->width_px : 0u, depth ? depth->height_px : 0u);
    // The previous frame's dispatch and indirect draw must be done with these buffers before the
    // host overwrites them; the resets below are ordered before the dispatch by GL itself.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    glNamedBufferSubData(params_.id(), 0, sizeof(params), &params);
    const gpu::DrawCommandGpu reset{0u, 1u, 0u, 0u};  // one instance, no vertices yet
    glNamedBufferSubData(targets.drawCommand.id(), 0, sizeof(reset), &reset);
    const std::uint32_t zero = 0;
    glClearNamedBufferSubData(targets.stats.id(), GL_R32UI, 0, sizeof(gpu::CullStatsGpu),
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
    if (patchCount == 0) return;

    program_.use();
    glBindBufferBase(GL_UNIFORM_BUFFER, CULL_UBO_BINDING, params_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_SSBO_BINDING, blades.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, PATCH_SSBO_BINDING, patches.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VISIBLE_INDEX_SSBO_BINDING,
                     targets.visibleIndices.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DRAW_COMMAND_SSBO_BINDING, targets.drawCommand.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CULL_STATS_SSBO_BINDING, targets.stats.id());
    glBindTextureUnit(CULL_DEPTH_TEXTURE_UNIT, depth ? depth->texture.id() : 0);
    gl::dispatchGroups(patchCount);
    // The draw reads the command (indirect) and the indices (SSBO); tests read back.
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
    context_.checkErrors("CullingPass::dispatch");
}

gpu::DrawCommandGpu CullingPass::readDrawCommand() const {
    gpu::DrawCommandGpu command{};
    glGetNamedBufferSubData(command_.id(), 0, sizeof(command), &command);
    return command;
}

gpu::CullStatsGpu CullingPass::readStats() const {
    gpu::CullStatsGpu stats{};
    glGetNamedBufferSubData(stats_.id(), 0, sizeof(stats), &stats);
    return stats;
}

}  // namespace meadow::runtime
