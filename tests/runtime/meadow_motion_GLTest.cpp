// The bundled meadow rendered for five seconds with its wind, as `meadow render` renders it:
// the grass must still cover the ground it covered at the first frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>

#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "meadow/runtime/scene.h"
#include "support/grass_pixels.h"

namespace meadow::runtime {
namespace {

using meadow::test::grassShare;

// Done when: after 5 s of the bundled scene with its wind, the grass-pixel share is at least
// 85 % of frame 0's. The camera is held still (the scene's own path moves it).
TEST(MeadowMotionGLTest, TheBundledMeadowKeepsItsGrassCoverForFiveSeconds) {
    SceneDescription scene = loadSceneDescription(std::filesystem::path(MEADOW_SOURCE_DIR) /
                                                  "samples" / "scenes" / "meadow.json");
    scene.camera.path.resize(1);
    scene.render.width_px = 192;
    scene.render.height_px = 108;
    scene.render.msaaSamples = 1;
    GlContext context;
    Renderer renderer(context, scene);
    installPhysicsPass(renderer, context);
    installCullingPass(renderer, context);
    constexpr int kLast = 150;  // 5 s at the scene's 30 Hz
    double first = 0.0, middle = 0.0, last = 0.0;
    renderer.renderFrames(0, kLast + 1, /*wantImages=*/true, [&](RenderedFrame&& f) {
        if (f.stats.frame == 0) first = grassShare(f.image_bgr);
        if (f.stats.frame == kLast / 2) middle = grassShare(f.image_bgr);
        if (f.stats.frame == kLast) last = grassShare(f.image_bgr);
    });
    ASSERT_GT(first, 0.1) << "the view must show grass";
    EXPECT_GE(middle, 0.85 * first) << "at 2.5 s: " << middle << " of the image, at 0 s " << first;
    EXPECT_GE(last, 0.85 * first) << "at 5 s: " << last << " of the image, at 0 s " << first;
}

}  // namespace
}  // namespace meadow::runtime
