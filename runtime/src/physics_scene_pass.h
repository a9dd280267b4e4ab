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

// How a frame's time step is simulated: at most kMaxFrame_s of it (a long hitch must not launch
// the blades), cut into substeps short enough for the explicit step to be stable for the
// stiffest blade (s dt <= 0.5; stable below 1).
struct PhysicsSubsteps {
    int count = 1;
    float step_s = 0.f;
};
[[nodiscard]] PhysicsSubsteps physicsSubsteps(float maxStiffness_per_s, float frameStep_s);

// Every collider's spheres where the collider is at time_s (it may move between sub-steps).
void collidersAt(const SceneDescription& scene, const SceneGpu& gpu, float time_s,
                 std::vector<CollisionSphere>& spheres);

}  // namespace meadow::runtime
