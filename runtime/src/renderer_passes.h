#pragma once
// The interface of the per-frame compute passes (physics, culling) the renderer runs between
// the depth pre-pass and the blade draw. All buffers of SceneGpu are bound at their blade_types.h
// binding points when run() is called.
#include "gl/gl_object.h"
#include "meadow/runtime/scene.h"
#include "scene_gpu.h"
#include "shared/blade_types.h"

namespace meadow::runtime {

struct PassInputs {
    const SceneDescription& scene;
    const SceneGpu& gpu;
    const gpu::FrameGpu& frame;  // also in the FRAME_UBO_BINDING uniform buffer
    const gl::Texture& depth;    // single-sample GL_DEPTH_COMPONENT32F of the opaque pre-pass
    float time_s;                // simulated time of this frame
    float deltaTime_s;           // since the previous frame (0 on the first)
};

class BladeComputePass {
public:
    virtual ~BladeComputePass() = default;
    // Dispatches the pass. A culling pass writes VISIBLE_INDEX, DRAW_COMMAND and CULL_STATS
    // (resetting the count and stats itself) and ends with the barriers the draw needs.
    virtual void run(const PassInputs& inputs) = 0;
};

}  // namespace meadow::runtime
