// The scene's objects for plant finding (scene_clusters.h): Euclidean clusters of what the
// plane removal leaves, parted where objects stand apart in the image or in depth.
#include "segmentation/scene_clusters.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "support/cast_scene.h"

namespace meadow::capture::segmentation::scene {
namespace {

using test::castScene;
using test::Strip;

std::vector<Cluster> clustersOf(const std::vector<Strip>& strips) {
    const Intrinsics k = Intrinsics::kinectV1();
    const cv::Mat1w depth = castScene(k, {}, strips);
    return euclideanClusters(depth, k, SegmenterParams{}, depth > 0);
}

TEST(SceneClusters, OneStripIsOneObjectWithItsSizeDepthAndBounds) {
    const Strip strip{-0.02f, 0.02f, -0.2f, 0.2f, 1.f};
    const std::vector<Cluster> c = clustersOf({strip});
    ASSERT_EQ(c.size(), 1u);
    const Intrinsics k = Intrinsics::kinectV1();
    const int drawn = cv::countNonZero(castScene(k, {}, strip) > 0);
    EXPECT_EQ(c[0].area_px, drawn) << "grown back to every reading";
    EXPECT_NEAR(c[0].medianDepth_m, 1.f, 0.002f);
    EXPECT_NEAR(c[0].height_m, 0.4f, 0.01f);
    // Bounds of the samples (every 2nd pixel, 1.7 mm apart at 1 m).
    EXPECT_NEAR(c[0].lo[0], -0.02f, 0.005f);
    EXPECT_NEAR(c[0].hi[0], 0.02f, 0.005f);
    EXPECT_NEAR(c[0].lo[1], -0.2f, 0.005f);
    EXPECT_NEAR(c[0].hi[1], 0.2f, 0.005f);
}

TEST(SceneClusters, StripsApartInTheImageAreTwoObjects) {
    const std::vector<Cluster> c =
        clustersOf({{-0.12f, -0.08f, -0.2f, 0.2f, 1.f}, {0.08f, 0.12f, -0.2f, 0.2f, 1.f}});
    ASSERT_EQ(c.size(), 2u);
    EXPECT_FALSE(boundsMeet(c[0], c[1], 0.03f)) << "16 cm apart";
    EXPECT_TRUE(boundsMeet(c[0], c[1], 0.2f));
}

TEST(SceneClusters, AStripBeforeAnotherIsApartFromIt) {
    // Side by side in the image, 30 cm apart in depth: the depth jump parts them.
    const std::vector<Cluster> c =
        clustersOf({{-0.05f, 0.f, -0.2f, 0.2f, 1.f}, {0.f, 0.065f, -0.26f, 0.26f, 1.3f}});
    ASSERT_EQ(c.size(), 2u);
    EXPECT_NEAR(std::min(c[0].medianDepth_m, c[1].medianDepth_m), 1.f, 0.01f);
    EXPECT_NEAR(std::max(c[0].medianDepth_m, c[1].medianDepth_m), 1.3f, 0.01f);
}

}  // namespace
}  // namespace meadow::capture::segmentation::scene
