#include "culling_scene_pass.h"

#include <algorithm>

#include "culling_pass.h"
#include "meadow/runtime/renderer.h"

namespace meadow::runtime {

CullSettings cullSettingsOf(const SceneDescription& scene) {
    CullSettings s;
    s.orientation = scene.culling.orientation;
    s.frustum = scene.culling.frustum;
    s.distance = scene.culling.distance;
    s.occlusion = scene.culling.occlusion;
    s.orientationThreshold = scene.culling.orientationThreshold;
    s.maxDistance_m = scene.culling.maxDistance_m;
    s.distanceLevels = static_cast<unsigned>(std::max(scene.culling.distanceLevels, 1));
    return s;
}

namespace {

class CullingComputePass final : public BladeComputePass {
public:
    // The pass's own visible-index buffer is not used (the scene's is), so it is kept minimal.
    explicit CullingComputePass(GlContext& context) : pass_(context, 1) {}

    void run(const PassInputs& in) override {
        const CullCamera camera{in.frame.clipFromWorld, glm::vec3(in.frame.cameraPosition_time),
                                in.frame.viewport_px.z, in.frame.viewport_px.w};
        const CullDepth depth{in.depth, static_cast<std::uint32_t>(in.frame.viewport_px.x),
                              static_cast<std::uint32_t>(in.frame.viewport_px.y)};
        pass_.dispatch(in.gpu.blades, in.gpu.bladeCount, in.gpu.patches, in.gpu.patchCount, camera,
                       cullSettingsOf(in.scene), &depth,
                       CullTargets{in.gpu.visibleIndices, in.gpu.bladeCount, in.gpu.drawCommand,
                                   in.gpu.cullStats});
    }

private:
    CullingPass pass_;
};

}  // namespace

std::unique_ptr<BladeComputePass> makeCullingComputePass(GlContext& context) {
    return std::make_unique<CullingComputePass>(context);
}

void installCullingPass(Renderer& renderer, GlContext& context) {
    renderer.setCullingPass(makeCullingComputePass(context));
}

}  // namespace meadow::runtime
