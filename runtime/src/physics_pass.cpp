#include "physics_pass.h"

#include "gl/dispatch.h"
#include "physics_reference.h"

namespace meadow::runtime {

namespace {
gl::ProgramSource physicsProgramSource() {
    return {
        .label = "blade physics",
        .stages = {{GL_COMPUTE_SHADER, "physics.comp"}},
        .commonFiles = {"shared/physics_params.h", "common_dispatch.glsl", "common_physics.glsl"},
        .defines = {}};
}
}  // namespace

PhysicsPass::PhysicsPass(GlContext& context)
    : context_(context),
      program_(physicsProgramSource()),
      params_(gl::Buffer::create()),
      colliders_(gl::Buffer::create()) {
    glNamedBufferStorage(params_.id(), sizeof(gpu::PhysicsParamsGpu), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    context_.checkErrors("PhysicsPass: creating buffers");
}

void PhysicsPass::dispatch(const gl::Buffer& blades, const gl::Buffer& rests,
                           std::uint32_t bladeCount, std::span<const CollisionSphere> spheres,
                           const PhysicsSettings& settings, float dt_s, float time_s) {
    if (bladeCount == 0) return;
    const std::vector<gpu::ColliderGpu> colliders = packColliders(spheres);
    // The SSBO binding needs a non-empty buffer even when there is nothing to collide with.
    const std::size_t capacity = std::max<std::size_t>(colliders.size(), 1);
    if (capacity > colliderCapacity_) {
        colliders_ = gl::Buffer::create();
        glNamedBufferStorage(colliders_.id(), capacity * sizeof(gpu::ColliderGpu), nullptr,
                             GL_DYNAMIC_STORAGE_BIT);
        colliderCapacity_ = capacity;
    }
    // Earlier dispatches may still read the uniform block and the colliders.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (!colliders.empty())
        glNamedBufferSubData(colliders_.id(), 0, colliders.size() * sizeof(gpu::ColliderGpu),
                             colliders.data());
    const gpu::PhysicsParamsGpu params = packPhysicsParams(
        settings, dt_s, time_s, bladeCount, static_cast<std::uint32_t>(colliders.size()));
    glNamedBufferSubData(params_.id(), 0, sizeof(params), &params);

    program_.use();
    glBindBufferBase(GL_UNIFORM_BUFFER, PHYSICS_UBO_BINDING, params_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_SSBO_BINDING, blades.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_REST_SSBO_BINDING, rests.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, COLLIDER_SSBO_BINDING, colliders_.id());
    gl::dispatchGroups((bladeCount + BLADE_WORKGROUP_SIZE - 1) / BLADE_WORKGROUP_SIZE);
    // Culling reads the blades as SSBOs, the draw pass in its shaders, tests by read-back.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    context_.checkErrors("PhysicsPass::dispatch");
}

}  // namespace meadow::runtime
