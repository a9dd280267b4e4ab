#pragma once
// The physics pass as the renderer runs it (renderer_passes.h): settings from the scene file,
// the frame's wind and time step, the scene's colliders moved to this frame's time.
#include <memory>

#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "renderer_passes.h"

namespace meadow::runtime {

// The PhysicsSettings a scene asks for (gravity, collision decay, wind; the rest default).
[[nodiscard]] PhysicsSettings physicsSettingsOf(const SceneDescription& scene,
                                                const gpu::FrameGpu& frame);
[[nodiscard]] std::unique_ptr<BladeComputePass> makePhysicsComputePass(GlContext& context);

}  // namespace meadow::runtime
