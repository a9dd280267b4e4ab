#pragma once
// The raster half of a frame: multisampled colour + depth target, depth pre-pass and shading of
// the opaque meshes, tessellated blades from the indirect draw command, MSAA resolve, and
// read-back or a copy into a window.
#include <opencv2/core/mat.hpp>
#include <optional>

#include "gl/gl_object.h"
#include "gl/shader_program.h"
#include "meadow/runtime/scene.h"
#include "scene_gpu.h"

namespace meadow::runtime {

class TiledField;

// CV_8UC3 BGR, top row first, from GL's RGBA8 rows, bottom row first.
[[nodiscard]] cv::Mat bgrFromBottomUpRgba(const void* rgba, int width_px, int height_px);

class DrawPass {
public:
    DrawPass(int width_px, int height_px, int msaaSamples);

    // Binds the multisampled target and clears it to the sky colour (display values) and far;
    // with a zenith colour, draws the sky's gradient (the frame's uniform block must be bound).
    void begin(const LightDescription& light);
    // Opaque meshes into depth only; the single-sample copy feeds occlusion culling.
    void depthPrepass(const SceneGpu& gpu) const;
    void resolveDepth() const;
    // The shadow cascades from the frame's lightClipFromWorld: opaque meshes and the blades of the
    // indirect draw (call after the culling or emit pass). Binds it for the shading passes.
    void renderShadowMap(const SceneGpu& gpu, const SceneDescription& scene);
    // Opaque meshes shaded where the pre-pass left their depth; the terrain with its far field.
    void shadeOpaque(const SceneGpu& gpu, const SceneDescription& scene, const TiledField* tiled,
                     float pixelSize_perM);
    // Blades of the visible-index buffer, as many as the indirect command says.
    void drawBlades(const SceneGpu& gpu, const SceneDescription& scene, float pixelSize_perM);
    void resolveColor() const;
    [[nodiscard]] cv::Mat readBack() const;  // CV_8UC3 BGR, top row first; waits for the GPU
    // Copies the resolved image into the current context's default framebuffer, scaled to
    // width_px x height_px.
    void blitToDefaultFramebuffer(int width_px, int height_px) const;
    // Blades as the edges of their triangles (glPolygonMode); the opaque meshes stay filled.
    void setWireframe(bool enabled) { wireframe_ = enabled; }
    // Queues a copy of the resolved image into `pixelPack` (RGBA8 rows, bottom first, at least
    // 4 * width * height bytes) on the GPU; read it once the frame's fence has signalled.
    void packColor(const gl::Buffer& pixelPack) const;

    [[nodiscard]] const gl::Texture& depthTexture() const { return resolvedDepth_; }
    // Bytes of the colour, depth and shadow targets.
    [[nodiscard]] std::size_t targetBytes() const;
    [[nodiscard]] int width_px() const { return width_; }
    [[nodiscard]] int height_px() const { return height_; }

private:
    // The blades of the indirect draw command with `program` (its uniforms set by the caller).
    void drawIndirectBlades(const SceneGpu& gpu, const gl::ShaderProgram& program);
    const gl::ShaderProgram& terrainProgram();

    int width_, height_, samples_;
    gl::Renderbuffer msaaColor_, msaaDepth_;
    gl::Framebuffer msaaTarget_;
    gl::Texture resolvedColor_, resolvedDepth_;
    gl::Framebuffer resolvedColorTarget_, resolvedDepthTarget_;
    gl::ShaderProgram opaqueProgram_, bladeProgram_, chunkProgram_;
    gl::Buffer chunks_;  // DrawCommandGpu[chunkCapacity_]
    std::uint32_t chunkCapacity_ = 0;
    gl::VertexArray emptyVertexArray_;  // the blade draw has no vertex attributes
    bool wireframe_ = false;
    // Made when a scene first needs them (each costs a compile).
    std::optional<gl::ShaderProgram> skyProgram_, terrainProgram_, opaqueShadowProgram_,
        bladeShadowProgram_;
    gl::Texture shadowMap_;
    gl::Framebuffer shadowTarget_;
    int shadowSize_ = 0;
};

}  // namespace meadow::runtime
