#pragma once
// The per-blade physics compute pass (shaders/physics.comp, Jahrmann & Wimmer 2017, Sec. 5): one
// step of forces, sphere collisions and validation on every blade, in place. It owns its program,
// its uniform block and the collider buffer; the blade buffers belong to the scene.
#include <cstdint>
#include <span>

#include "gl/gl_object.h"
#include "gl/shader_program.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"

namespace meadow::runtime {

class PhysicsPass {
public:
    // Compiles physics.comp; throws RuntimeError on a compile or link error.
    explicit PhysicsPass(GlContext& context);

    // One step of dt_s at time_s on the first bladeCount blades of `blades` (BladeGpu[]) and
    // `rests` (BladeRestGpu[]), pushed by `spheres`. Ends with the memory barriers that let the
    // culling and draw passes (and a read-back) see the result.
    void dispatch(const gl::Buffer& blades, const gl::Buffer& rests, std::uint32_t bladeCount,
                  std::span<const CollisionSphere> spheres, const PhysicsSettings& settings,
                  float dt_s, float time_s);

private:
    GlContext& context_;
    gl::ShaderProgram program_;
    gl::Buffer params_;
    gl::Buffer colliders_;
    std::size_t colliderCapacity_ = 0;
};

}  // namespace meadow::runtime
