// The renderer as `meadow view` drives it: a caller's camera and clock, culling and wireframe
// switched at run time, and a window's context adopted instead of a headless one.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/core.hpp>

#include "gl/gl_api.h"
#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/renderer.h"
#include "meadow/runtime/scene.h"

namespace meadow::runtime {
namespace {

// The sample scene, small: thousands of blades seen across a field, some of them culled.
SceneDescription sampleScene(int width_px = 160, int height_px = 90) {
    SceneDescription scene = loadSceneDescription(std::filesystem::path(MEADOW_SOURCE_DIR) /
                                                  "samples/scenes/meadow.json");
    scene.render.width_px = width_px;
    scene.render.height_px = height_px;
    return scene;
}

ViewFrame firstKeyAtTimeZero(const SceneDescription& scene) {
    ViewFrame view;
    view.camera = {scene.camera.path.front().position_m, scene.camera.path.front().target_m};
    view.wantStats = true;
    view.wantImage = true;
    return view;
}

bool isGreen(const cv::Vec3b& bgr) { return bgr[1] > bgr[2] && bgr[1] > bgr[0]; }

// Of the pixels of the bottom quarter (the nearest blades) green in `filled`, the share not
// green in `wire`.
double shareOpenedInBottomQuarter(const cv::Mat& filled, const cv::Mat& wire) {
    int green = 0, opened = 0;
    for (int y = filled.rows * 3 / 4; y < filled.rows; ++y)
        for (int x = 0; x < filled.cols; ++x)
            if (isGreen(filled.at<cv::Vec3b>(y, x))) {
                ++green;
                opened += !isGreen(wire.at<cv::Vec3b>(y, x));
            }
    return green ? static_cast<double>(opened) / green : 0.0;
}

TEST(RenderViewGLTest, ViewOfTheFirstKeyAtTimeZeroIsFrameZero) {
    GlContext context;
    const SceneDescription scene = sampleScene();
    Renderer rendered(context, scene);
    installCullingPass(rendered, context);
    const RenderedFrame frame = rendered.renderFrame(0);
    Renderer viewed(context, scene);
    installCullingPass(viewed, context);
    const RenderedFrame view = viewed.renderView(firstKeyAtTimeZero(scene));
    ASSERT_EQ(view.image_bgr.size(), frame.image_bgr.size());
    EXPECT_EQ(cv::norm(view.image_bgr, frame.image_bgr, cv::NORM_INF), 0.0);
    EXPECT_EQ(view.stats.bladesDrawn, frame.stats.bladesDrawn);
    EXPECT_EQ(view.stats.culledFrustum, frame.stats.culledFrustum);
}

TEST(RenderViewGLTest, ViewReadsBackNothingUnlessAsked) {
    GlContext context;
    const SceneDescription scene = sampleScene();
    Renderer renderer(context, scene);
    ViewFrame view = firstKeyAtTimeZero(scene);
    view.wantImage = view.wantStats = false;
    const RenderedFrame frame = renderer.renderView(view);
    EXPECT_TRUE(frame.image_bgr.empty());
    EXPECT_EQ(frame.stats.bladesDrawn, 0u);
    EXPECT_EQ(frame.stats.bladesTotal, renderer.bladeCount());
}

TEST(RenderViewGLTest, CullingOffDrawsEveryBladeAndOnCullsAsBefore) {
    GlContext context;
    const SceneDescription scene = sampleScene();
    const ViewFrame view = firstKeyAtTimeZero(scene);
    Renderer neverCulled(context, scene);  // no culling pass: the reference for "all drawn"
    const cv::Mat all = neverCulled.renderView(view).image_bgr.clone();

    Renderer renderer(context, scene);
    installCullingPass(renderer, context);
    const RenderedFrame on = renderer.renderView(view);
    ASSERT_LT(on.stats.bladesDrawn, on.stats.bladesTotal) << "the view culls nothing to compare";
    renderer.setCullingEnabled(false);
    const RenderedFrame off = renderer.renderView(view);
    EXPECT_EQ(off.stats.bladesDrawn, off.stats.bladesTotal);
    EXPECT_EQ(off.stats.culledFrustum + off.stats.culledDistance + off.stats.culledOrientation +
                  off.stats.culledOcclusion,
              0u);
    // The culled frame's compacted indices were replaced by every blade's.
    EXPECT_EQ(cv::norm(off.image_bgr, all, cv::NORM_INF), 0.0);
    renderer.setCullingEnabled(true);
    const RenderedFrame again = renderer.renderView(view);
    EXPECT_EQ(again.stats.bladesDrawn, on.stats.bladesDrawn);
    EXPECT_EQ(cv::norm(again.image_bgr, on.image_bgr, cv::NORM_INF), 0.0);
}

TEST(RenderViewGLTest, WireframeOpensTheNearBladesAndTurnsBackOff) {
    GlContext context;
    const SceneDescription scene = sampleScene(640, 360);
    // Close to the ground, where blades are many pixels wide and their edges leave gaps.
    ViewFrame view = firstKeyAtTimeZero(scene);
    view.camera = {{0.f, 0.8f, 1.5f}, {0.f, 0.2f, 0.f}};
    Renderer renderer(context, scene);
    const cv::Mat filled = renderer.renderView(view).image_bgr.clone();
    renderer.setWireframe(true);
    const cv::Mat wire = renderer.renderView(view).image_bgr.clone();
    // The near blades, many pixels wide, show the ground between their edges.
    const double opened = shareOpenedInBottomQuarter(filled, wire);
    EXPECT_GT(opened, 0.1) << "share of near blade pixels the wireframe leaves open";
    renderer.setWireframe(false);
    EXPECT_EQ(cv::norm(renderer.renderView(view).image_bgr, filled, cv::NORM_INF), 0.0);
}

TEST(RenderViewGLTest, AdoptedContextDescribesTheCurrentOneAndLeavesItCurrent) {
    GlContext owner(GlContextOptions{.debugOutput = false});
    {
        const GlContext adopted = GlContext::adoptCurrent(GlContextOptions{.debugOutput = false});
        EXPECT_EQ(adopted.renderer(), owner.renderer());
        EXPECT_EQ(adopted.version(), owner.version());
    }
    EXPECT_NE(glGetString(GL_VERSION), nullptr) << "adopting must not release the context";
    EXPECT_NO_THROW(owner.checkErrors("after an adopted context ended"));
}

}  // namespace
}  // namespace meadow::runtime
