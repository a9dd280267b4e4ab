#include "draw_pass.h"

#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <string>

#include "gl/dispatch.h"
#include "meadow/runtime/error.h"
#include "tiled_field.h"

namespace meadow::runtime {
namespace {

// Tessellation: one segment along the blade per this many pixels of projected length (a curve
// looks smooth at about 8 px per straight piece).
constexpr float kPixelsPerSegment = 8.f;

std::vector<gl::ShaderDefine> shadowDefines(bool shadowPass) {
    if (!shadowPass) return {};
    return {{"SHADOW_PASS", "1"}};
}

gl::ShaderProgram makeOpaqueProgram(bool shadowPass = false) {
    return gl::ShaderProgram({.label = shadowPass ? "opaque meshes (shadow map)" : "opaque meshes",
                              .stages = {{GL_VERTEX_SHADER, "depth_prepass.vert"},
                                         {GL_FRAGMENT_SHADER, "depth_prepass.frag"}},
                              .commonFiles = {"common_shading.glsl"},
                              .defines = shadowDefines(shadowPass)});
}

gl::ShaderProgram makeChunkProgram() {
    return gl::ShaderProgram({.label = "blade draw chunks",
                              .stages = {{GL_COMPUTE_SHADER, "blade_chunks.comp"}},
                              .commonFiles = {"common_dispatch.glsl"},
                              .defines = {}});
}

gl::ShaderProgram makeBladeProgram(bool shadowPass = false) {
    std::vector<gl::ShaderDefine> defines = shadowDefines(shadowPass);
    defines.push_back({"BLADE_PIXELS_PER_SEGMENT", std::to_string(kPixelsPerSegment)});
    return gl::ShaderProgram({.label = shadowPass ? "blades (shadow map)" : "blades",
                              .stages = {{GL_VERTEX_SHADER, "blade.vert"},
                                         {GL_TESS_CONTROL_SHADER, "blade.tesc"},
                                         {GL_TESS_EVALUATION_SHADER, "blade.tese"},
                                         {GL_FRAGMENT_SHADER, "blade.frag"}},
                              .commonFiles = {"common_blade.glsl", "common_shading.glsl"},
                              .defines = defines});
}

void checkComplete(const gl::Framebuffer& fb, const char* what) {
    const GLenum status = glCheckNamedFramebufferStatus(fb.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%X", status);
        throw RuntimeError(std::string("meadow::runtime: the ") + what +
                           " framebuffer is incomplete (status " + hex +
                           "); lower render.msaa_samples or render.size_px");
    }
}

}  // namespace

DrawPass::DrawPass(int width_px, int height_px, int msaaSamples)
    : width_(width_px),
      height_(height_px),
      samples_(msaaSamples),
      msaaColor_(gl::Renderbuffer::create()),
      msaaDepth_(gl::Renderbuffer::create()),
      msaaTarget_(gl::Framebuffer::create()),
      resolvedColor_(gl::Texture::create(GL_TEXTURE_2D)),
      resolvedDepth_(gl::Texture::create(GL_TEXTURE_2D)),
      resolvedColorTarget_(gl::Framebuffer::create()),
      resolvedDepthTarget_(gl::Framebuffer::create()),
      opaqueProgram_(makeOpaqueProgram()),
      bladeProgram_(makeBladeProgram()),
      chunkProgram_(makeChunkProgram()),
      emptyVertexArray_(gl::VertexArray::create()) {
    GLint maxSamples = 1;
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    samples_ = std::min(samples_, maxSamples);
    glNamedRenderbufferStorageMultisample(msaaColor_.id(), samples_, GL_RGBA8, width_, height_);
    glNamedRenderbufferStorageMultisample(msaaDepth_.id(), samples_, GL_DEPTH_COMPONENT32F, width_,
                                          height_);
    glNamedFramebufferRenderbuffer(msaaTarget_.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                                   msaaColor_.id());
    glNamedFramebufferRenderbuffer(msaaTarget_.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                   msaaDepth_.id());
    checkComplete(msaaTarget_, "multisampled");

    glTextureStorage2D(resolvedColor_.id(), 1, GL_RGBA8, width_, height_);
    glNamedFramebufferTexture(resolvedColorTarget_.id(), GL_COLOR_ATTACHMENT0, resolvedColor_.id(),
                              0);
    checkComplete(resolvedColorTarget_, "resolved colour");
    glTextureStorage2D(resolvedDepth_.id(), 1, GL_DEPTH_COMPONENT32F, width_, height_);
    glTextureParameteri(resolvedDepth_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(resolvedDepth_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glNamedFramebufferTexture(resolvedDepthTarget_.id(), GL_DEPTH_ATTACHMENT, resolvedDepth_.id(),
                              0);
    glNamedFramebufferDrawBuffer(resolvedDepthTarget_.id(), GL_NONE);
    checkComplete(resolvedDepthTarget_, "resolved depth");
}

void DrawPass::begin(const LightDescription& light) {
    const glm::vec3 sky = light.skyColor;
    glBindFramebuffer(GL_FRAMEBUFFER, msaaTarget_.id());
    glViewport(0, 0, width_, height_);
    glEnable(GL_MULTISAMPLE);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const float color[4] = {sky.r, sky.g, sky.b, 1.f};
    const float far = 1.f;
    glClearNamedFramebufferfv(msaaTarget_.id(), GL_COLOR, 0, color);
    glClearNamedFramebufferfv(msaaTarget_.id(), GL_DEPTH, 0, &far);
    if (!light.zenithColor) return;
    if (!skyProgram_)
        skyProgram_.emplace(gl::ProgramSource{
            .label = "sky",
            .stages = {{GL_VERTEX_SHADER, "sky.vert"}, {GL_FRAGMENT_SHADER, "sky.frag"}},
            .commonFiles = {"common_shading.glsl"},
            .defines = {}});
    glDisable(GL_DEPTH_TEST);
    skyProgram_->use();
    glBindVertexArray(emptyVertexArray_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
}

const gl::ShaderProgram& DrawPass::terrainProgram() {
    if (!terrainProgram_)
        terrainProgram_.emplace(gl::ProgramSource{
            .label = "terrain and far field",
            .stages = {{GL_VERTEX_SHADER, "depth_prepass.vert"},
                       {GL_FRAGMENT_SHADER, "terrain.frag"}},
            .commonFiles = {"shared/physics_params.h", "shared/tiling_types.h",
                            "common_physics.glsl", "common_tiles.glsl", "common_shading.glsl"},
            .defines = {}});
    return *terrainProgram_;
}

void DrawPass::depthPrepass(const SceneGpu& gpu) const {
    glBindFramebuffer(GL_FRAMEBUFFER, msaaTarget_.id());
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    opaqueProgram_.use();
    for (const GpuMesh& m : gpu.meshes) {
        if (!m.visible) continue;
        opaqueProgram_.set("uOffset_m", m.offset_m);
        glBindVertexArray(m.vertexArray.id());
        glDrawElements(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr);
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void DrawPass::resolveDepth() const {
    // Multisampled depth resolves by picking one sample (GL_NEAREST is the only filter allowed).
    glBlitNamedFramebuffer(msaaTarget_.id(), resolvedDepthTarget_.id(), 0, 0, width_, height_, 0, 0,
                           width_, height_, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void DrawPass::shadeOpaque(const SceneGpu& gpu, const SceneDescription& scene,
                           const TiledField* tiled, float pixelSize_perM) {
    glBindFramebuffer(GL_FRAMEBUFFER, msaaTarget_.id());
    // The same vertex shader as the pre-pass with gl_Position invariant, so the depths match
    // exactly, also for the terrain's own program; nothing is written twice.
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    if (tiled) {
        tiled->bindForShading();
        const gl::ShaderProgram& t = terrainProgram();
        t.use();
        const FarFieldSlices& slices = tiled->farField();
        t.set("uFarField", tiled->hasFarField() ? 1 : 0);
        t.set("uSlicesPerAxis", slices.perAxis);
        t.set("uSliceSpacing_m", slices.spacing_m);
        t.set("uSliceHeight_m", slices.height_m);
        t.set("uPixelSize_perM", pixelSize_perM);
        t.set("uTranslucency", scene.render.translucency);
        for (int b = 0; b < FarFieldSlices::kHeightBands; ++b) {
            const std::string i = "[" + std::to_string(b) + "]";
            t.set(("uBandCoverage" + i).c_str(), slices.bandCoverage[static_cast<std::size_t>(b)]);
            t.set(("uBandAlbedo" + i).c_str(), slices.bandAlbedo[static_cast<std::size_t>(b)]);
        }
        t.set("uAmbient", scene.light.ambient);
    }
    opaqueProgram_.use();
    opaqueProgram_.set("uAmbient", scene.light.ambient);
    for (const GpuMesh& m : gpu.meshes) {
        if (!m.visible) continue;
        const gl::ShaderProgram& program = m.terrain ? terrainProgram() : opaqueProgram_;
        program.use();
        program.set("uAlbedo", m.albedo);
        program.set("uOffset_m", m.offset_m);
        glBindVertexArray(m.vertexArray.id());
        glDrawElements(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr);
    }
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
}

void DrawPass::drawBlades(const SceneGpu& gpu, const SceneDescription& scene,
                          float pixelSize_perM) {
    const RenderSettings& r = scene.render;
    glBindFramebuffer(GL_FRAMEBUFFER, msaaTarget_.id());
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);  // blades are two-sided
    bladeProgram_.use();
    bladeProgram_.set("uMaxTessLevel", r.maxTessLevel);
    bladeProgram_.set("uAcrossSegments", r.displacement ? 2 : 1);
    bladeProgram_.set("uShapeOverride", r.shapeOverride);
    bladeProgram_.set("uDisplacement", r.displacement ? 1 : 0);
    bladeProgram_.set("uPixelSize_perM", pixelSize_perM);
    bladeProgram_.set("uMinWidth_px", r.minWidth_px);
    bladeProgram_.set("uRootColor", r.rootColor);
    bladeProgram_.set("uTipColor", r.tipColor);
    bladeProgram_.set("uAmbient", scene.light.ambient);
    bladeProgram_.set("uTranslucency", r.translucency);
    bladeProgram_.set("uAoAtRoot", r.aoAtRoot);
    if (wireframe_) glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    drawIndirectBlades(gpu, bladeProgram_);
    if (wireframe_) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void DrawPass::drawIndirectBlades(const SceneGpu& gpu, const gl::ShaderProgram& program) {
    glBindVertexArray(emptyVertexArray_.id());
    glPatchParameteri(GL_PATCH_VERTICES, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    // The culling pass's one command becomes chunkCount commands of BLADE_DRAW_CHUNK blades.
    const std::uint32_t chunkCount = (gpu.bladeCount + BLADE_DRAW_CHUNK - 1) / BLADE_DRAW_CHUNK;
    if (chunkCapacity_ < chunkCount) {
        chunks_ = gl::Buffer::create();
        glNamedBufferStorage(chunks_.id(), chunkCount * sizeof(gpu::DrawCommandGpu), nullptr, 0);
        chunkCapacity_ = chunkCount;
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DRAW_CHUNK_SSBO_BINDING, chunks_.id());
    chunkProgram_.use();
    chunkProgram_.set("uChunkCount", static_cast<unsigned>(chunkCount));
    gl::dispatchGroups((chunkCount + BLADE_WORKGROUP_SIZE - 1) / BLADE_WORKGROUP_SIZE);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT);
    program.use();
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, chunks_.id());
    glMultiDrawArraysIndirect(GL_PATCHES, nullptr, static_cast<GLsizei>(chunkCount), 0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

void DrawPass::renderShadowMap(const SceneGpu& gpu, const SceneDescription& scene) {
    const int size = scene.shadows.mapSize_px;
    if (shadowSize_ != size) {
        shadowMap_ = gl::Texture::create(GL_TEXTURE_2D);
        glTextureStorage2D(shadowMap_.id(), 1, GL_DEPTH_COMPONENT32F, size * SHADOW_CASCADES, size);
        glTextureParameteri(shadowMap_.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(shadowMap_.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(shadowMap_.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(shadowMap_.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTextureParameteri(shadowMap_.id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(shadowMap_.id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
        shadowTarget_ = gl::Framebuffer::create();
        glNamedFramebufferTexture(shadowTarget_.id(), GL_DEPTH_ATTACHMENT, shadowMap_.id(), 0);
        glNamedFramebufferDrawBuffer(shadowTarget_.id(), GL_NONE);
        checkComplete(shadowTarget_, "shadow map");
        shadowSize_ = size;
        opaqueShadowProgram_.emplace(makeOpaqueProgram(true));
        bladeShadowProgram_.emplace(makeBladeProgram(true));
    }
    glBindTextureUnit(SHADOW_TEXTURE_UNIT, 0);  // not sampled while it is drawn into
    glBindFramebuffer(GL_FRAMEBUFFER, shadowTarget_.id());
    const float far = 1.f;
    glClearNamedFramebufferfv(shadowTarget_.id(), GL_DEPTH, 0, &far);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_MULTISAMPLE);
    const RenderSettings& r = scene.render;
    const gl::ShaderProgram& blades = *bladeShadowProgram_;
    blades.use();
    // A shadow needs the blade's shape, not its detail.
    blades.set("uMaxTessLevel", std::min(r.maxTessLevel, 4.f));
    blades.set("uAcrossSegments", 1);
    blades.set("uShapeOverride", r.shapeOverride);
    blades.set("uDisplacement", 0);
    blades.set("uPixelSize_perM", 0.f);
    blades.set("uMinWidth_px", 0.f);
    // Cascade c is the c-th size x size square of the map.
    for (int cascade = 0; cascade < SHADOW_CASCADES; ++cascade) {
        glViewport(cascade * size, 0, size, size);
        opaqueShadowProgram_->use();
        opaqueShadowProgram_->set("uShadowCascade", cascade);
        for (const GpuMesh& m : gpu.meshes) {
            if (!m.visible) continue;
            opaqueShadowProgram_->set("uOffset_m", m.offset_m);
            glBindVertexArray(m.vertexArray.id());
            glDrawElements(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr);
        }
        blades.use();
        blades.set("uShadowCascade", cascade);
        drawIndirectBlades(gpu, blades);
    }
    glEnable(GL_MULTISAMPLE);
    glBindFramebuffer(GL_FRAMEBUFFER, msaaTarget_.id());
    glViewport(0, 0, width_, height_);
    glBindTextureUnit(SHADOW_TEXTURE_UNIT, shadowMap_.id());
}

std::size_t DrawPass::targetBytes() const {
    const std::size_t pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    // Multisampled RGBA8 + depth32F, resolved RGBA8 + depth32F, the shadow map's depth32F.
    return pixels * static_cast<std::size_t>(samples_) * 8 + pixels * 8 +
           static_cast<std::size_t>(shadowSize_) * static_cast<std::size_t>(shadowSize_) * 4 *
               SHADOW_CASCADES;
}

void DrawPass::resolveColor() const {
    glBlitNamedFramebuffer(msaaTarget_.id(), resolvedColorTarget_.id(), 0, 0, width_, height_, 0, 0,
                           width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void DrawPass::blitToDefaultFramebuffer(int width_px, int height_px) const {
    const bool sameSize = width_px == width_ && height_px == height_;
    glBlitNamedFramebuffer(resolvedColorTarget_.id(), 0, 0, 0, width_, height_, 0, 0, width_px,
                           height_px, GL_COLOR_BUFFER_BIT, sameSize ? GL_NEAREST : GL_LINEAR);
}

cv::Mat bgrFromBottomUpRgba(const void* rgba, int width_px, int height_px) {
    const cv::Mat view(height_px, width_px, CV_8UC4, const_cast<void*>(rgba));  // not written
    cv::Mat bgr;
    cv::cvtColor(view, bgr, cv::COLOR_RGBA2BGR);
    cv::flip(bgr, bgr, 0);  // GL's first row is the bottom one
    return bgr;
}

cv::Mat DrawPass::readBack() const {
    cv::Mat rgba(height_, width_, CV_8UC4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(resolvedColor_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE,
                      static_cast<GLsizei>(rgba.total() * 4), rgba.data);
    return bgrFromBottomUpRgba(rgba.data, width_, height_);
}

void DrawPass::packColor(const gl::Buffer& pixelPack) const {
    glBindBuffer(GL_PIXEL_PACK_BUFFER, pixelPack.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    // With a pixel-pack buffer bound the pointer is an offset into it: no wait for the GPU.
    glGetTextureImage(resolvedColor_.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE,
                      static_cast<GLsizei>(std::size_t{4} * width_ * height_), nullptr);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

}  // namespace meadow::runtime
