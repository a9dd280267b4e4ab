#pragma once
// The culling pass as the renderer runs it (renderer_passes.h): the frame's camera, the scene's
// culling settings, the opaque depth pre-pass, writing the scene's visible indices, draw command
// and stats.
#include <memory>

#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "renderer_passes.h"

namespace meadow::runtime {

[[nodiscard]] CullSettings cullSettingsOf(const SceneDescription& scene);
[[nodiscard]] std::unique_ptr<BladeComputePass> makeCullingComputePass(GlContext& context);

}  // namespace meadow::runtime
