// A rendered frame of a tiny scene: grass where it grows, sky where nothing is, repeatable.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/renderer.h"
#include "meadow/runtime/scene.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

SceneDescription tinyMeadow() {
    return loadSceneDescription(test::writeSmallMeadow(test::freshTestDirectory("render")));
}

bool isGreen(const cv::Vec3b& bgr) { return test::isGreen(bgr[0], bgr[1], bgr[2]); }

TEST(RenderGLTest, TinyMeadowHasGrassBelowAndSkyAbove) {
    GlContext context;
    const SceneDescription scene = tinyMeadow();
    Renderer renderer(context, scene);
    const RenderedFrame frame = renderer.renderFrame(0);
    const cv::Mat& image = frame.image_bgr;
    ASSERT_EQ(image.cols, 96);
    ASSERT_EQ(image.rows, 64);
    ASSERT_EQ(image.type(), CV_8UC3);

    // Top rows: sky, exactly the clear colour (display values).
    const cv::Vec3b sky(static_cast<uchar>(std::lround(0.9 * 255)),
                        static_cast<uchar>(std::lround(0.75 * 255)),
                        static_cast<uchar>(std::lround(0.6 * 255)));
    for (int x = 0; x < image.cols; ++x)
        ASSERT_LE(cv::norm(image.at<cv::Vec3b>(1, x), sky, cv::NORM_INF), 1.0)
            << "sky pixel at x " << x;
    // Grass region (middle of the lower half): mostly green.
    int green = 0, total = 0;
    for (int y = image.rows / 2; y < image.rows * 3 / 4; ++y)
        for (int x = image.cols / 4; x < image.cols * 3 / 4; ++x, ++total)
            green += isGreen(image.at<cv::Vec3b>(y, x));
    EXPECT_GT(green, total / 3) << green << " green of " << total << " pixels in the grass region";

    const FrameStats& s = frame.stats;
    EXPECT_EQ(s.bladesTotal, renderer.bladeCount());
    EXPECT_EQ(s.bladesDrawn + s.culledOrientation + s.culledFrustum + s.culledDistance +
                  s.culledOcclusion,
              s.bladesTotal);
    for (double t : {s.gpuPrepass_ms, s.gpuDraw_ms, s.gpuResolve_ms, s.frame_ms})
        EXPECT_TRUE(std::isfinite(t) && t >= 0);
}

TEST(RenderGLTest, SameSceneRendersTheSameImageTwice) {
    GlContext context;
    const SceneDescription scene = tinyMeadow();
    cv::Mat first;
    {
        Renderer renderer(context, scene);
        first = renderer.renderFrame(0).image_bgr.clone();
    }
    Renderer renderer(context, scene);
    const cv::Mat second = renderer.renderFrame(0).image_bgr;
    EXPECT_EQ(cv::norm(first, second, cv::NORM_INF), 0.0);
}

TEST(RenderGLTest, EveryAnalyticShapeAndDisplacementDrawsGrass) {
    GlContext context;
    for (int shape = 0; shape < 5; ++shape) {
        SceneDescription scene = tinyMeadow();
        scene.render.shapeOverride = shape;
        scene.render.displacement = shape % 2 == 1;
        Renderer renderer(context, scene);
        const cv::Mat image = renderer.renderFrame(0).image_bgr;
        int green = 0;
        for (int y = image.rows / 2; y < image.rows; ++y)
            for (int x = 0; x < image.cols; ++x) green += isGreen(image.at<cv::Vec3b>(y, x));
        EXPECT_GT(green, image.total() / 8)
            << "shape " << shape << " displacement " << scene.render.displacement;
    }
}

}  // namespace
}  // namespace meadow::runtime
