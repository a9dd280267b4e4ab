#pragma once
// Renders a scene frame by frame: depth pre-pass of the opaque meshes -> physics (compute) ->
// culling (compute, writes the indirect draw) -> opaque shading -> tessellated blades -> MSAA
// resolve -> read-back. GPU timer queries time each stage.
#include <functional>
#include <glm/vec3.hpp>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <string>

#include "meadow/runtime/frame_stats.h"
#include "meadow/runtime/scene.h"

namespace meadow::runtime {

class GlContext;
class BladeComputePass;  // runtime/src/renderer_passes.h
struct SceneBlades;      // runtime/src/scene_gpu.h

struct RenderedFrame {
    cv::Mat image_bgr;  // CV_8UC3, width x height of the scene (or the override)
    FrameStats stats;
};

// Where the camera is and what it looks at, world space.
struct CameraPose {
    glm::vec3 position_m{0.f};
    glm::vec3 target_m{0.f, 0.f, -1.f};
};

// One frame of an interactive view (`meadow view`): the caller's camera and clock instead of the
// scene's camera path and frame rate.
struct ViewFrame {
    CameraPose camera;
    float time_s = 0.f;       // simulated time shown (wind, moving colliders)
    float deltaTime_s = 0.f;  // physics step since the previous frame; 0 holds the blades still
    bool wantStats = false;   // read counts and GPU times back (waits for the GPU)
    bool wantImage = false;   // read the image back (waits for the GPU)
};

class Renderer {
public:
    // Loads meshes, seeds the blades, builds patches and uploads everything. `context` must
    // outlive the renderer and be current on this thread. Throws RuntimeError.
    Renderer(GlContext& context, const SceneDescription& scene);
    // The same with blades the caller placed (runtime/src/scene_gpu.h) instead of the scene's
    // seeding: tests and tools that need blades at known poses. The scene's meshes still load.
    Renderer(GlContext& context, const SceneDescription& scene, SceneBlades blades);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Frame i shows simulated time i / render.frame_rate_hz; frames must be rendered in order
    // for the physics to integrate (the blades' state lives on the GPU).
    // Synchronous: returns once the frame is on the CPU (image, counts, GPU times), so the CPU
    // waits for the GPU every frame. frame_ms: wall time of the call, read-back included.
    RenderedFrame renderFrame(int frameIndex);

    // Pipelined: renders frames first .. first + count - 1 (count >= 0) and hands each to
    // onFrame, in order, with the same images and stats renderFrame would give. Up to three
    // frames are on the GPU at once; frame k is collected (its fence waited for, its copies
    // mapped) only after frame k + 2 has been submitted, and the last ones when the call drains,
    // so the CPU never waits on the frame it has just submitted. image_bgr stays empty unless
    // wantImages. frame_ms: the renderer's wall time from the start of this frame's submission
    // to the start of the next one's (for the last frame of the call, to its collection), time
    // spent in onFrame left out; the frame_ms of a call add up to its wall time minus onFrame.
    // If onFrame throws, the frames still in flight are dropped.
    void renderFrames(int first, int count, bool wantImages,
                      const std::function<void(RenderedFrame&&)>& onFrame);

    // Renders one frame of `view` up to the resolved image on the GPU, for a window to show with
    // blitToDefaultFramebuffer(). Frames must come in time order for the physics, as above.
    // Reads back only what `view` asks for, so a frame left unread never makes the CPU wait;
    // stats.frame counts the calls, frame_ms is the call's wall time.
    RenderedFrame renderView(const ViewFrame& view);
    // Copies the last frame's resolved image into the default framebuffer of the current context
    // (a window's back buffer), scaled to width_px x height_px, without a read-back.
    void blitToDefaultFramebuffer(int width_px, int height_px) const;
    // Off: the culling pass is skipped and every blade is drawn. On by default.
    void setCullingEnabled(bool enabled);
    // On: blades are drawn as the edges of their tessellated triangles. Off by default.
    void setWireframe(bool enabled);

    // Blades planted: stored ones, or for a tiled scene the patch on every tile after the
    // density map.
    [[nodiscard]] std::size_t bladeCount() const;
    // GPU memory of the scene's buffers and textures and the render targets, bytes (what meadow
    // allocated; the driver's own overhead is not counted).
    [[nodiscard]] std::size_t gpuMemoryBytes() const;
    [[nodiscard]] std::size_t patchCount() const;
    // One line on what is drawn, e.g. "22016 blades in 86 patches" or "134206920 blades on
    // 62500 tiles of one 2176-blade patch".
    [[nodiscard]] std::string summary() const;

    // The compute passes (physics, culling) plug in here; without them blades keep their rest
    // pose and all are drawn.
    void setPhysicsPass(std::unique_ptr<BladeComputePass> pass);
    void setCullingPass(std::unique_ptr<BladeComputePass> pass);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace meadow::runtime
