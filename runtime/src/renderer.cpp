#include "meadow/runtime/renderer.h"

#include <array>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "draw_pass.h"
#include "gl/gl_object.h"
#include "meadow/runtime/error.h"
#include "meadow/runtime/gl_context.h"
#include "renderer_passes.h"
#include "scene_gpu.h"

namespace meadow::runtime {
namespace {

enum Stage { kPrepass, kPhysics, kCulling, kDraw, kResolve, kStageCount };
constexpr double kMillisecondsPerNanosecond = 1e-6;

struct CameraPose {
    glm::vec3 position_m, target_m;
};

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

glm::mat4 viewFromWorldOf(const CameraPose& pose) {
    const glm::vec3 forward = glm::normalize(pose.target_m - pose.position_m);
    // World +Y is up unless the camera looks straight up or down.
    const glm::vec3 up =
        std::abs(forward.y) > 0.999f ? glm::vec3(0.f, 0.f, -1.f) : glm::vec3(0.f, 1.f, 0.f);
    return glm::lookAt(pose.position_m, pose.target_m, up);
}

}  // namespace

struct Renderer::Impl {
    GlContext& context;
    SceneDescription scene;
    SceneBlades blades;
    SceneGpu gpu;
    DrawPass draw;
    std::array<gl::Query, kStageCount> timers;
    std::unique_ptr<BladeComputePass> physics, culling;
    float previousTime_s = -1.f;

    Impl(GlContext& c, const SceneDescription& s)
        : context(c),
          scene(s),
          blades(buildSceneBlades(s)),
          gpu(uploadScene(blades, s)),
          draw(s.render.width_px, s.render.height_px, s.render.msaaSamples) {
        for (gl::Query& q : timers) q = gl::Query::create(GL_TIME_ELAPSED);
        context.checkErrors("uploading the scene " + s.file.string());
    }
};

Renderer::Renderer(GlContext& context, const SceneDescription& scene)
    : impl_(std::make_unique<Impl>(context, scene)) {}
Renderer::~Renderer() = default;

std::size_t Renderer::bladeCount() const { return impl_->gpu.bladeCount; }
std::size_t Renderer::patchCount() const { return impl_->gpu.patchCount; }
void Renderer::setPhysicsPass(std::unique_ptr<BladeComputePass> pass) {
    impl_->physics = std::move(pass);
}
void Renderer::setCullingPass(std::unique_ptr<BladeComputePass> pass) {
    impl_->culling = std::move(pass);
}

RenderedFrame Renderer::renderFrame(int frameIndex) {
    Impl& im = *impl_;
    const SceneDescription& scene = im.scene;
    const auto start = std::chrono::steady_clock::now();
    const float time_s = static_cast<float>(frameIndex) / scene.render.frameRate_hz;
    const float deltaTime_s = im.previousTime_s < 0.f ? 0.f : time_s - im.previousTime_s;
    im.previousTime_s = time_s;

    const CameraPose pose = cameraAt(scene.camera, time_s);
    const float aspect =
        static_cast<float>(im.draw.width_px()) / static_cast<float>(im.draw.height_px());
    const glm::mat4 clipFromView =
        glm::perspective(glm::radians(scene.camera.verticalFov_deg), aspect, scene.camera.near_m,
                         scene.camera.far_m);
    gpu::FrameGpu frame{};
    frame.viewFromWorld = viewFromWorldOf(pose);
    frame.clipFromWorld = clipFromView * frame.viewFromWorld;
    frame.cameraPosition_time = glm::vec4(pose.position_m, time_s);
    frame.lightDirection = glm::vec4(scene.light.direction, scene.light.intensity);
    frame.viewport_px =
        glm::vec4(im.draw.width_px(), im.draw.height_px(), scene.camera.near_m, scene.camera.far_m);
    frame.wind = glm::vec4(scene.wind.direction, scene.wind.waveAmplitude_m_s);
    glNamedBufferSubData(im.gpu.frame.id(), 0, sizeof frame, &frame);
    // World size of one pixel at 1 m: the image height spans 2 tan(fov / 2) at unit distance.
    const float pixelSize_perM =
        2.f / (clipFromView[1][1] * static_cast<float>(im.draw.height_px()));

    std::array<bool, kStageCount> ran{};
    auto timed = [&](Stage stage, auto&& work) {
        glBeginQuery(GL_TIME_ELAPSED, im.timers[stage].id());
        work();
        glEndQuery(GL_TIME_ELAPSED);
        ran[stage] = true;
    };

    im.gpu.bindAll();
    im.draw.begin(scene.light.skyColor);
    timed(kPrepass, [&] {
        im.draw.depthPrepass(im.gpu);
        im.draw.resolveDepth();
    });
    const PassInputs inputs{scene, im.gpu, frame, im.draw.depthTexture(), time_s, deltaTime_s};
    if (im.physics && scene.physics.enabled) timed(kPhysics, [&] { im.physics->run(inputs); });
    if (im.culling)
        timed(kCulling, [&] { im.culling->run(inputs); });
    else
        im.gpu.fillTrivialVisibility();
    im.gpu.bindAll();  // a pass may have bound other buffers
    timed(kDraw, [&] {
        im.draw.shadeOpaque(im.gpu, scene);
        im.draw.drawBlades(im.gpu, scene, pixelSize_perM);
    });
    timed(kResolve, [&] { im.draw.resolveColor(); });

    RenderedFrame out;
    out.image_bgr = im.draw.readBack();
    gpu::DrawCommandGpu command{};
    gpu::CullStatsGpu culled{};
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(im.gpu.drawCommand.id(), 0, sizeof command, &command);
    glGetNamedBufferSubData(im.gpu.cullStats.id(), 0, sizeof culled, &culled);

    FrameStats& st = out.stats;
    st.frame = frameIndex;
    st.time_s = time_s;
    st.bladesTotal = im.gpu.bladeCount;
    st.bladesDrawn = command.vertexCount;
    st.culledOrientation = culled.culledOrientation;
    st.culledFrustum = culled.culledFrustum;
    st.culledDistance = culled.culledDistance;
    st.culledOcclusion = culled.culledOcclusion;
    double* gpuTimes[kStageCount] = {&st.gpuPrepass_ms, &st.gpuPhysics_ms, &st.gpuCulling_ms,
                                     &st.gpuDraw_ms, &st.gpuResolve_ms};
    for (int s = 0; s < kStageCount; ++s) {
        if (!ran[s]) continue;
        GLuint64 elapsed_ns = 0;
        glGetQueryObjectui64v(im.timers[s].id(), GL_QUERY_RESULT, &elapsed_ns);
        *gpuTimes[s] = static_cast<double>(elapsed_ns) * kMillisecondsPerNanosecond;
    }
    im.context.checkErrors("rendering frame " + std::to_string(frameIndex) + " of " +
                           scene.file.string());
    st.frame_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace meadow::runtime
