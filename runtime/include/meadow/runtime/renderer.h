#pragma once
// Renders a scene frame by frame: depth pre-pass of the opaque meshes -> physics (compute) ->
// culling (compute, writes the indirect draw) -> opaque shading -> tessellated blades -> MSAA
// resolve -> read-back. GPU timer queries time each stage.
#include <memory>
#include <opencv2/core/mat.hpp>

#include "meadow/runtime/frame_stats.h"
#include "meadow/runtime/scene.h"

namespace meadow::runtime {

class GlContext;
class BladeComputePass;  // runtime/src/renderer_passes.h

struct RenderedFrame {
    cv::Mat image_bgr;  // CV_8UC3, width x height of the scene (or the override)
    FrameStats stats;
};

class Renderer {
public:
    // Loads meshes, seeds the blades, builds patches and uploads everything. `context` must
    // outlive the renderer and be current on this thread. Throws RuntimeError.
    Renderer(GlContext& context, const SceneDescription& scene);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Frame i shows simulated time i / render.frame_rate_hz; frames must be rendered in order
    // for the physics to integrate (the blades' state lives on the GPU).
    RenderedFrame renderFrame(int frameIndex);

    [[nodiscard]] std::size_t bladeCount() const;
    [[nodiscard]] std::size_t patchCount() const;

    // The compute passes (physics, culling) plug in here; without them blades keep their rest
    // pose and all are drawn.
    void setPhysicsPass(std::unique_ptr<BladeComputePass> pass);
    void setCullingPass(std::unique_ptr<BladeComputePass> pass);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace meadow::runtime
