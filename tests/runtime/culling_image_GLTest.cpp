// What culling costs the picture: a small field seen across, as the sample scene does, rendered
// once with every culling test on (the scene defaults) and once with culling off (same seed, same
// frame, physics off). Culling is only worth its name if a person would not notice it: few pixels
// change by more than a small colour step and the grass coverage stays the same.
#include <gtest/gtest.h>

#include <cstdlib>
#include <opencv2/core.hpp>
#include <sstream>

#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/renderer.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

// A colour step (max over B, G, R, of 255) a person does not see between two thin-blade images.
constexpr int kColourStep = 24;
// Bounds: at most 0.5 % of the pixels change by more than kColourStep (scattered single pixels),
// and the grass coverage moves by at most 2 % of itself (thin grass is ~15 % of this image, so
// 2 % of the image would let a seventh of the grass go). The paper's orientation threshold 0.9
// with distance culling from 5 m breaks both on this view: a visibly thinner meadow.
constexpr double kMaxPixelsDiffering = 0.005;
constexpr double kMaxRelativeCoverageChange = 0.02;

// Grass-coloured: green clearly above red (the brown ground) and blue (the sky).
bool isGrass(const cv::Vec3b& bgr) { return bgr[1] > bgr[2] + 8 && bgr[1] > bgr[0] + 8; }

struct ImageDifference {
    double pixelsDiffering = 0.0;  // fraction of the image
    double coverageCulled = 0.0;   // grass fraction of the culled image
    double coverageAll = 0.0;      // grass fraction with everything drawn
};

ImageDifference compare(const cv::Mat& culled, const cv::Mat& all) {
    ImageDifference d;
    const double n = static_cast<double>(culled.total());
    for (int y = 0; y < culled.rows; ++y)
        for (int x = 0; x < culled.cols; ++x) {
            const cv::Vec3b a = culled.at<cv::Vec3b>(y, x), b = all.at<cv::Vec3b>(y, x);
            int step = 0;
            for (int k = 0; k < 3; ++k) step = std::max(step, std::abs(int(a[k]) - int(b[k])));
            d.pixelsDiffering += step > kColourStep ? 1.0 : 0.0;
            d.coverageCulled += isGrass(a) ? 1.0 : 0.0;
            d.coverageAll += isGrass(b) ? 1.0 : 0.0;
        }
    d.pixelsDiffering /= n;
    d.coverageCulled /= n;
    d.coverageAll /= n;
    return d;
}

TEST(CullingImageGLTest, CullingWithDefaultSettingsDoesNotChangeTheImageNoticeably) {
    const auto dir = test::freshTestDirectory("culling_image");
    // 8 m x 10 m of ground in front of and beyond the camera's target, a few thousand blades.
    test::writeQuad(dir / "ground.gltf", -4.f, 4.f, -6.f, 4.f);
    const nlohmann::json extra = {
        {"blades", {{"density_per_m2", 50}, {"seed", 5}}},
        {"camera",
         {{"path", {{{"time_s", 0}, {"position_m", {0, 1.6, 5.5}}, {"target_m", {0, 0.2, 0}}}}},
          {"vertical_fov_deg", 50},
          {"near_m", 0.05},
          {"far_m", 100}}},
        {"physics", {{"enabled", false}}},
        {"render", {{"size_px", {320, 180}}, {"msaa_samples", 4}, {"patch_size", 64}}}};
    const SceneDescription scene =
        loadSceneDescription(test::writeScene(dir, test::minimalScene("ground.gltf", extra)));

    GlContext context;
    Renderer culledRenderer(context, scene);
    installCullingPass(culledRenderer, context);
    const RenderedFrame culled = culledRenderer.renderFrame(0);
    Renderer allRenderer(context, scene);  // no culling pass: every blade is drawn
    const RenderedFrame all = allRenderer.renderFrame(0);

    const FrameStats& s = culled.stats;  // every culling test on, the scene defaults
    const ImageDifference d = compare(culled.image_bgr, all.image_bgr);
    std::ostringstream numbers;
    numbers << "blades " << s.bladesTotal << ", drawn " << s.bladesDrawn << " (orientation "
            << s.culledOrientation << ", frustum " << s.culledFrustum << ", distance "
            << s.culledDistance << ", occlusion " << s.culledOcclusion << " culled); pixels "
            << "differing by > " << kColourStep << ": " << 100.0 * d.pixelsDiffering
            << " %; grass coverage " << 100.0 * d.coverageCulled << " % culled vs "
            << 100.0 * d.coverageAll << " % all drawn";
    std::cout << "[ culling image ] " << numbers.str() << "\n";

    ASSERT_EQ(all.stats.bladesDrawn, all.stats.bladesTotal) << numbers.str();
    ASSERT_EQ(culled.image_bgr.size(), all.image_bgr.size());
    EXPECT_GT(d.coverageAll, 0.1) << "too little grass in view to judge: " << numbers.str();
    EXPECT_LT(s.bladesDrawn, s.bladesTotal) << "nothing was culled: " << numbers.str();
    EXPECT_GT(s.culledOrientation, 0u) << numbers.str();
    EXPECT_GT(s.culledFrustum, 0u) << numbers.str();
    EXPECT_LE(d.pixelsDiffering, kMaxPixelsDiffering) << numbers.str();
    EXPECT_LE(std::abs(d.coverageCulled - d.coverageAll),
              kMaxRelativeCoverageChange * d.coverageAll)
        << numbers.str();
}

}  // namespace
}  // namespace meadow::runtime
