#include "meadow/runtime/renderer.h"

#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "draw_pass.h"
#include "frame_setup.h"
#include "frame_slots.h"
#include "gl/gl_object.h"
#include "meadow/runtime/error.h"
#include "meadow/runtime/gl_context.h"
#include "renderer_passes.h"
#include "scene_gpu.h"
#include "tiled_field.h"

namespace meadow::runtime {
namespace {

// Linear interpolation along the key frames, held constant before the first and after the last.
CameraPose cameraAt(const CameraDescription& camera, float time_s) {
    const auto& path = camera.path;
    if (time_s <= path.front().time_s) return {path.front().position_m, path.front().target_m};
    for (std::size_t i = 1; i < path.size(); ++i)
        if (time_s <= path[i].time_s) {
            const float f = (time_s - path[i - 1].time_s) / (path[i].time_s - path[i - 1].time_s);
            return {glm::mix(path[i - 1].position_m, path[i].position_m, f),
                    glm::mix(path[i - 1].target_m, path[i].target_m, f)};
        }
    return {path.back().position_m, path.back().target_m};
}

// A culling pass compacts the visible blades to the front of the index buffer; drawing all of
// them again needs every index back in place.
void restoreAllVisible(const SceneGpu& gpu) {
    std::vector<std::uint32_t> all(gpu.bladeCount);
    std::iota(all.begin(), all.end(), 0u);
    glNamedBufferSubData(gpu.visibleIndices.id(), 0,
                         static_cast<GLsizeiptr>(all.size() * sizeof(std::uint32_t)), all.data());
}

}  // namespace

struct Renderer::Impl {
    GlContext& context;
    SceneDescription scene;
    SceneBlades blades;
    SceneGpu gpu;
    DrawPass draw;
    StageTimers timers;  // renderFrame's
    FrameSlots slots;    // renderFrames'
    std::unique_ptr<BladeComputePass> physics, culling;
    std::unique_ptr<TiledField> tiled;  // a tiled scene's patch, pool and passes
    float previousTime_s = -1.f;
    bool cullingEnabled = true;
    bool visibleIndicesAreAll = true;  // false once a culling pass has compacted them
    int viewFrames = 0;                // renderView's calls so far

    Impl(GlContext& c, const SceneDescription& s) : Impl(c, s, buildSceneBlades(s)) {}
    // Camera keys, targets and collider paths of a terrain with relative heights, on the ground.
    static SceneDescription placedOnTerrain(SceneDescription s, const SceneBlades& b) {
        if (!b.terrain || !s.terrain || !s.terrain->relativeHeights) return s;
        const auto lift = [&](glm::vec3& p) { p.y += b.terrain->heightAt({p.x, p.z}); };
        for (CameraKey& k : s.camera.path) {
            lift(k.position_m);
            lift(k.target_m);
        }
        for (ColliderDescription& c : s.colliders) {
            lift(c.center_m);
            for (ColliderKey& k : c.path) lift(k.position_m);
        }
        return s;
    }
    Impl(GlContext& c, const SceneDescription& s, SceneBlades b)
        : context(c),
          scene(placedOnTerrain(s, b)),
          blades(std::move(b)),
          gpu(uploadScene(blades, s)),
          draw(s.render.width_px, s.render.height_px, s.render.msaaSamples),
          slots(draw.width_px(), draw.height_px()) {
        if (blades.terrain)
            tiled = std::make_unique<TiledField>(context, scene, *blades.terrain, blades.tilePatch);
        context.checkErrors("uploading the scene " + s.file.string());
    }

    // Issues every GL command of frame `frameIndex` up to the MSAA resolve, timed by `frameTimers`,
    // and returns the CPU-side part of its stats (frame, time, blade total). Reads nothing back.
    FrameStats recordFrame(int frameIndex, StageTimers& frameTimers);
    // The same for any camera and clock; stats.frame is left 0.
    FrameStats recordFrameAt(const CameraPose& pose, float time_s, float deltaTime_s,
                             StageTimers& frameTimers);
    // Stored blades, or a tiled scene's patch on every tile (Renderer::bladeCount).
    [[nodiscard]] std::uint64_t plantedBlades() const {
        return tiled ? tiled->instancedBlades() : gpu.bladeCount;
    }
    // The counts of the frame just recorded (waits for the GPU).
    void readCounts(FrameStats& stats) const;
};

Renderer::Renderer(GlContext& context, const SceneDescription& scene)
    : impl_(std::make_unique<Impl>(context, scene)) {}
Renderer::Renderer(GlContext& context, const SceneDescription& scene, SceneBlades blades)
    : impl_(std::make_unique<Impl>(context, scene, std::move(blades))) {}
Renderer::~Renderer() = default;

std::size_t Renderer::bladeCount() const { return impl_->plantedBlades(); }
std::size_t Renderer::gpuMemoryBytes() const {
    const Impl& im = *impl_;
    const SceneGpu& g = im.gpu;
    std::size_t bytes =
        std::size_t{g.bladeCount} *
            (sizeof(gpu::BladeGpu) + sizeof(gpu::BladeRestGpu) + sizeof(std::uint32_t)) +
        std::size_t{g.patchCount} * sizeof(gpu::PatchGpu) +
        im.blades.archetypes.size() * sizeof(gpu::ArchetypeGpu);
    for (const GpuMesh& m : g.meshes)
        bytes += static_cast<std::size_t>(m.indexCount) * sizeof(std::uint32_t) +
                 static_cast<std::size_t>(m.vertexCount) * 6 * sizeof(float);
    bytes += im.draw.targetBytes();
    if (im.tiled) bytes += im.tiled->gpuBytes();
    return bytes;
}

std::string Renderer::summary() const {
    if (const TiledField* t = impl_->tiled.get())
        return std::to_string(impl_->plantedBlades()) + " blades on " +
               std::to_string(static_cast<std::size_t>(t->grid().tilesX()) *
                              static_cast<std::size_t>(t->grid().tilesZ())) +
               " tiles of one " + std::to_string(t->patchBlades()) + "-blade patch";
    return std::to_string(impl_->gpu.bladeCount) + " blades in " +
           std::to_string(impl_->gpu.patchCount) + " patches";
}

std::size_t Renderer::patchCount() const { return impl_->gpu.patchCount; }
void Renderer::setPhysicsPass(std::unique_ptr<BladeComputePass> pass) {
    impl_->physics = std::move(pass);
}
void Renderer::setCullingPass(std::unique_ptr<BladeComputePass> pass) {
    impl_->culling = std::move(pass);
}
void Renderer::setCullingEnabled(bool enabled) { impl_->cullingEnabled = enabled; }
void Renderer::setWireframe(bool enabled) { impl_->draw.setWireframe(enabled); }

FrameStats Renderer::Impl::recordFrame(int frameIndex, StageTimers& frameTimers) {
    const float time_s = static_cast<float>(frameIndex) / scene.render.frameRate_hz;
    const float deltaTime_s = previousTime_s < 0.f ? 0.f : time_s - previousTime_s;
    FrameStats st = recordFrameAt(cameraAt(scene.camera, time_s), time_s, deltaTime_s, frameTimers);
    st.frame = frameIndex;
    return st;
}

FrameStats Renderer::Impl::recordFrameAt(const CameraPose& pose, float time_s, float deltaTime_s,
                                         StageTimers& frameTimers) {
    previousTime_s = time_s;
    const gpu::FrameGpu frame = frameGpuOf(scene, pose, time_s, draw.width_px(), draw.height_px());
    glNamedBufferSubData(gpu.frame.id(), 0, sizeof frame, &frame);
    const float pixelSize_perM = pixelSizePerMetre(scene, draw.height_px());

    frameTimers.reset();
    gpu.placeColliders(scene, time_s);
    gpu.bindAll();
    draw.begin(scene.light);
    frameTimers.time(kPrepass, [&] {
        draw.depthPrepass(gpu);
        draw.resolveDepth();
    });
    const PassInputs inputs{scene, gpu, frame, draw.depthTexture(), time_s, deltaTime_s};
    if (tiled) {
        // Tiles simulate and emit their own blades; the stored-blade passes have none to work on.
        frameTimers.time(kPhysics, [&] { tiled->simulate(inputs); });
        frameTimers.time(kCulling, [&] { tiled->emit(inputs); });
    } else {
        if (physics && scene.physics.enabled)
            frameTimers.time(kPhysics, [&] { physics->run(inputs); });
        if (culling && cullingEnabled) {
            frameTimers.time(kCulling, [&] { culling->run(inputs); });
            visibleIndicesAreAll = false;
        } else {
            if (!visibleIndicesAreAll) {
                restoreAllVisible(gpu);
                visibleIndicesAreAll = true;
            }
            gpu.fillTrivialVisibility();
        }
    }
    gpu.bindAll();  // a pass may have bound other buffers
    if (scene.shadows.enabled)
        frameTimers.time(kShadows, [&] { draw.renderShadowMap(gpu, scene); });
    frameTimers.time(kDraw, [&] {
        // Blades first: the opaque meshes behind them (a tiled scene's terrain with its far
        // field, the costliest fragments) then fail the depth test before they are shaded.
        draw.drawBlades(gpu, scene, pixelSize_perM);
        draw.shadeOpaque(gpu, scene, tiled.get(), pixelSize_perM);
    });
    frameTimers.time(kResolve, [&] { draw.resolveColor(); });

    FrameStats st;
    st.time_s = time_s;
    st.bladesTotal = plantedBlades();
    if (tiled) {
        st.tilesDrawn = tiled->tilesDrawn();
        st.tilesSimulated = tiled->pool().activeCount();
    }
    return st;
}

void Renderer::Impl::readCounts(FrameStats& stats) const {
    gpu::DrawCommandGpu command{};
    gpu::CullStatsGpu culled{};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(gpu.drawCommand.id(), 0, sizeof command, &command);
    glGetNamedBufferSubData(gpu.cullStats.id(), 0, sizeof culled, &culled);
    setCounts(stats, command, culled);
}

RenderedFrame Renderer::renderFrame(int frameIndex) {
    Impl& im = *impl_;
    const auto start = std::chrono::steady_clock::now();
    RenderedFrame out;
    out.stats = im.recordFrame(frameIndex, im.timers);
    out.image_bgr = im.draw.readBack();
    im.readCounts(out.stats);
    im.timers.readInto(out.stats);
    im.context.checkErrors("rendering frame " + std::to_string(frameIndex) + " of " +
                           im.scene.file.string());
    out.stats.frame_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

RenderedFrame Renderer::renderView(const ViewFrame& view) {
    Impl& im = *impl_;
    const auto start = std::chrono::steady_clock::now();
    RenderedFrame out;
    out.stats = im.recordFrameAt(view.camera, view.time_s, view.deltaTime_s, im.timers);
    out.stats.frame = im.viewFrames++;
    if (view.wantImage) out.image_bgr = im.draw.readBack();
    if (view.wantStats) {
        im.readCounts(out.stats);
        im.timers.readInto(out.stats);
    }
    im.context.checkErrors("rendering view frame " + std::to_string(out.stats.frame) + " of " +
                           im.scene.file.string());
    out.stats.frame_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

void Renderer::blitToDefaultFramebuffer(int width_px, int height_px) const {
    impl_->draw.blitToDefaultFramebuffer(width_px, height_px);
}

void Renderer::renderFrames(int first, int count, bool wantImages,
                            const std::function<void(RenderedFrame&&)>& onFrame) {
    if (first < 0 || count < 0)
        throw std::invalid_argument("Renderer::renderFrames: first (" + std::to_string(first) +
                                    ") and count (" + std::to_string(count) +
                                    ") must not be negative");
    Impl& im = *impl_;
    FrameSlots& slots = im.slots;
    slots.clear();  // an earlier call that threw may have left frames behind
    // The renderer's own clock: wall time since the call began, time spent in onFrame left out.
    const auto start = std::chrono::steady_clock::now();
    double inCallback_ms = 0.0;
    auto now_ms = [&] {
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                   .count() -
               inCallback_ms;
    };
    auto deliverOldest = [&] {
        const FrameSlot& oldest = slots.waitOldest();
        const double submitted_ms = oldest.submitted_ms;
        const bool hasSuccessor = slots.pendingCount() > 1;
        const double successor_ms = hasSuccessor ? slots.secondOldestSubmitted_ms() : 0.0;
        RenderedFrame frame = slots.takeOldest();
        frame.stats.frame_ms = (hasSuccessor ? successor_ms : now_ms()) - submitted_ms;
        im.context.checkErrors("collecting frame " + std::to_string(frame.stats.frame) + " of " +
                               im.scene.file.string());
        const auto callbackStart = std::chrono::steady_clock::now();
        onFrame(std::move(frame));
        inCallback_ms += std::chrono::duration<double, std::milli>(
                             std::chrono::steady_clock::now() - callbackStart)
                             .count();
    };
    for (int k = 0; k < count; ++k) {
        FrameSlot& slot = slots.next();
        slot.submitted_ms = now_ms();
        slot.stats = im.recordFrame(first + k, slot.timers);
        slots.submit(im.gpu.drawCommand, im.gpu.cullStats, wantImages ? &im.draw : nullptr);
        im.context.checkErrors("rendering frame " + std::to_string(first + k) + " of " +
                               im.scene.file.string());
        // With every slot pending, the oldest frame was submitted kFramesInFlight - 1 frames ago:
        // the GPU still has the newer ones queued while the CPU waits for it.
        if (slots.full()) deliverOldest();
    }
    while (slots.pendingCount() > 0) deliverOldest();
}

}  // namespace meadow::runtime
