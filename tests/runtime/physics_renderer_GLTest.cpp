// The physics and culling passes plugged into the renderer (installPhysicsPass /
// installCullingPass), on a small scene: every blade is either drawn or culled by exactly one
// test, and both compute stages run (their GPU timer queries report time).
#include <gtest/gtest.h>

#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

TEST(PhysicsRendererGLTest, InstalledPassesSimulateAndCullEveryBladeOnceInTheRenderer) {
    const auto dir = test::freshTestDirectory("physics_renderer");
    test::writeQuad(dir / "ground.gltf", -3.f, 3.f, -3.f, 3.f);
    const auto file = test::writeScene(
        dir,
        test::minimalScene("ground.gltf",
                           {{"colliders", {{{"center_m", {0.0, 0.1, 0.0}}, {"radius_m", 0.3}}}}}));
    const SceneDescription scene = loadSceneDescription(file);
    GlContext context;
    Renderer renderer(context, scene);
    installPhysicsPass(renderer, context);
    installCullingPass(renderer, context);
    for (int frame = 0; frame < 2; ++frame) {
        const RenderedFrame f = renderer.renderFrame(frame);
        const FrameStats& s = f.stats;
        SCOPED_TRACE("frame " + std::to_string(frame));
        EXPECT_EQ(s.bladesTotal, renderer.bladeCount());
        EXPECT_EQ(s.bladesDrawn + s.culledOrientation + s.culledFrustum + s.culledDistance +
                      s.culledOcclusion,
                  s.bladesTotal);
        EXPECT_GT(s.bladesDrawn, 0u);
        EXPECT_LT(s.bladesDrawn, s.bladesTotal) << "nothing was culled";
        EXPECT_GT(s.gpuCulling_ms, 0.0);
        if (frame > 0) {  // braces: EXPECT_* expands to an if/else (-Wdangling-else)
            EXPECT_GT(s.gpuPhysics_ms, 0.0);
        }
    }
}

}  // namespace
}  // namespace meadow::runtime
