// Rooting a segmented blade at its tuft's base (blade_root.h), on a synthetic blade whose lowest
// part is cut off, as the segmenter cuts a tuft's blades at their fork.
#include "meadow/modeling/blade_root.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

#include "meadow/capture/blade_contour.h"
#include "meadow/modeling/blade_fit.h"
#include "modeling/blade_fit_synthetic_test.h"

namespace meadow::modeling {
namespace {

using test::fineIntrinsics;
using test::makeBlade;
using test::renderBlade;

// A straight blade 0.12 m tall; the rendered (visible) part starts 30 mm above the true root.
constexpr float kHidden_m = 0.03f;

struct Cut {
    test::SyntheticBlade visible;
    glm::vec3 root_m;
    Skeleton skeleton;
};

Cut cutBlade() {
    const glm::vec3 root{0.f, 0.08f, 0.5f};
    Cut c{makeBlade(root + glm::vec3(0.f, -kHidden_m, 0.f), 0.12f - kHidden_m, 0.f, 0.006f),
          root,
          {}};
    const auto view = renderBlade(c.visible, fineIntrinsics(), 0.9f);
    c.skeleton = extractSkeleton(view.blade, view.frame);
    return c;
}

ClusterBase baseAt(const glm::vec3& p_m) {
    ClusterBase b;
    b.base_m = p_m;
    b.base_px = fineIntrinsics().project(p_m);
    b.depth_m = p_m.z;
    b.depthReadings = 9;
    return b;
}

TEST(BladeRoot, ExtendsTheSkeletonStraightDownToTheTuftBaseKeepingThePointCount) {
    Cut c = cutBlade();
    const std::size_t n = c.skeleton.points_m.size();
    const glm::vec3 tip = c.skeleton.points_m.back();
    rootSkeleton(c.skeleton, baseAt(c.root_m));
    EXPECT_FALSE(c.skeleton.baseNotRooted);
    ASSERT_EQ(c.skeleton.points_m.size(), n);
    EXPECT_EQ(c.skeleton.width_m.size(), n);
    EXPECT_EQ(c.skeleton.midline_px.size(), n);
    EXPECT_LT(glm::distance(c.skeleton.points_m.front(), c.root_m), 1e-6f);
    EXPECT_LT(glm::distance(c.skeleton.points_m.back(), tip), 1e-6f);
    EXPECT_NEAR(c.skeleton.baseExtension_m, kHidden_m, 1e-3f);
    // About a quarter of the points (30 of 120 mm) lie on the added piece, with the blade's width.
    EXPECT_NEAR(static_cast<float>(c.skeleton.rootPoints) / static_cast<float>(n), 0.25f, 0.03f);
    EXPECT_NEAR(c.skeleton.width_m.front(), 0.006f, 0.6e-3f);
    const BladeFit fit = fitArchetype(c.skeleton);
    EXPECT_NEAR(fit.archetype.height_m(), 0.12f, 1.5e-3f) << "height " << fit.archetype.height_m();
    EXPECT_NEAR(fit.archetype.fit.baseExtension_mm, kHidden_m * 1e3f, 1.f);
    EXPECT_FALSE(fit.archetype.fit.baseNotRooted);
}

TEST(BladeRoot, RefusesAndFlagsABaseFarFromTheBlade) {
    Cut c = cutBlade();
    const std::vector<glm::vec3> before = c.skeleton.points_m;
    // 0.3 m below: more than the blade's visible length (90 mm) away.
    rootSkeleton(c.skeleton, baseAt(c.root_m + glm::vec3(0.f, 0.3f, 0.f)));
    EXPECT_TRUE(c.skeleton.baseNotRooted);
    EXPECT_EQ(c.skeleton.points_m, before);
    EXPECT_EQ(c.skeleton.baseExtension_m, 0.f);
    ASSERT_FALSE(c.skeleton.reasons.empty());
    EXPECT_NE(c.skeleton.reasons.back().find("not rooted"), std::string::npos);
    EXPECT_TRUE(fitArchetype(c.skeleton).archetype.fit.baseNotRooted);
}

TEST(BladeRoot, RefusesABaseAboveTheBladesLowerEnd) {
    Cut c = cutBlade();
    const std::vector<glm::vec3> before = c.skeleton.points_m;
    rootSkeleton(c.skeleton, baseAt(c.skeleton.points_m[40]));  // up the blade
    EXPECT_TRUE(c.skeleton.baseNotRooted);
    EXPECT_EQ(c.skeleton.points_m, before);
}

// A leaf cut from a stem (a cluster with a stem line) whose outline, where it meets the stem and
// its neighbours, flares to 31 px across its lowest 16 px, on a leaf 9 px wide: the leaf is not
// rooted (it starts at its own base), and its lowest widths are bounded as a fork's are, by the
// widths just above them.
TEST(BladeRoot, ALeafCutFromAStemHasTheFlareWhereItMeetsTheStemBounded) {
    const capture::Intrinsics k = fineIntrinsics();
    cv::Mat1b drawn = cv::Mat1b::zeros(k.height_px, k.width_px);
    const cv::Point base(600, 700), tip(600, 400);
    cv::line(drawn, base, tip, 255, 9);
    cv::rectangle(drawn, cv::Rect(base.x - 15, base.y - 16, 31, 16), 255, cv::FILLED);
    std::vector<std::vector<cv::Point>> outlines;
    cv::findContours(drawn, outlines, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    ASSERT_EQ(outlines.size(), 1u);
    std::vector<cv::Point> outline = outlines[0];
    std::rotate(outline.begin(), outline.begin() + capture::nearestPointIndex(outline, base),
                outline.end());
    capture::Segmentation seg;
    seg.clusterMask = drawn;
    capture::BladeContour leaf;
    leaf.id = 1;
    leaf.contour_px = outline;
    leaf.tipIndex = capture::nearestPointIndex(outline, tip);
    leaf.mask = drawn;
    seg.blades.push_back(leaf);
    capture::BladeCluster cluster;
    cluster.bladeIds = {1};
    cluster.basePoint_px = cv::Point2f(base);
    cluster.stemLine_px = {{base.x, base.y + 40}, base};
    seg.clusters.push_back(cluster);
    capture::DepthFrame frame;
    frame.intrinsics = k;
    frame.depth_mm = cv::Mat1w(drawn.size(), std::uint16_t{0});
    frame.depth_mm.setTo(500, drawn);
    const Skeleton s = segmentedBladeSkeleton(seg, 0, frame, BladeFitParams{});
    EXPECT_EQ(s.baseExtension_m, 0.f) << "starts at its own base";
    EXPECT_FALSE(s.baseNotRooted);
    ASSERT_FALSE(s.width_px.empty());
    const float widest = *std::max_element(s.width_px.begin(), s.width_px.end());
    EXPECT_LT(widest, 14.f) << "the leaf is 9 px wide; the flare 31 px";
    EXPECT_GT(widest, 7.f);
}

// A cluster mask of rows 100..200 x columns 50..70 at 0.5 m, its base point where the segmenter
// puts it (the centroid of its lowest rows, a few rows above its bottom), optionally a ground.
struct FlatCluster {
    capture::Segmentation segmentation;
    capture::DepthFrame frame;
};

FlatCluster flatCluster(std::optional<cv::Vec4f> ground = std::nullopt) {
    FlatCluster c;
    c.frame.intrinsics = fineIntrinsics();
    c.frame.depth_mm =
        cv::Mat1w(fineIntrinsics().height_px, fineIntrinsics().width_px, std::uint16_t{500});
    c.segmentation.clusterMask = cv::Mat1b::zeros(c.frame.depth_mm.size());
    c.segmentation.clusterMask(cv::Rect(50, 100, 21, 101)).setTo(255);
    capture::BladeCluster cluster;
    cluster.basePoint_px = {60.f, 197.5f};
    cluster.bladeIds = {1};
    c.segmentation.clusters.push_back(cluster);
    c.segmentation.groundPlane = ground;
    return c;
}

TEST(ClusterBase, SitsOnTheClustersLowestRowNotOnTheCentroidOfItsLowestBand) {
    const FlatCluster c = flatCluster();
    const auto base = clusterBase(c.segmentation, 1, c.frame);
    ASSERT_TRUE(base);
    EXPECT_FLOAT_EQ(base->base_px.x, 60.f);
    EXPECT_FLOAT_EQ(base->base_px.y, 200.5f) << "the lower edge of row 200";
    EXPECT_FLOAT_EQ(base->depth_m, 0.5f);
    EXPECT_EQ(base->groundDrop_m, 0.f) << "no ground plane given";
    RootParams off;
    off.toLowestRow = false;
    EXPECT_FLOAT_EQ(clusterBase(c.segmentation, 1, c.frame, off)->base_px.y, 197.5f);
}

TEST(ClusterBase, DropsOntoAGroundPlaneJustBelowItAndIgnoresOneFarOrAbove) {
    const FlatCluster plain = flatCluster();
    const glm::vec3 visible = clusterBase(plain.segmentation, 1, plain.frame)->base_m;
    // Level ground (normal up: camera -y, as y is down) below_m under the visible base:
    // n.x + d = 0 at y = visible.y + below_m.
    const auto groundAt = [&](float below_m) {
        return cv::Vec4f(0.f, -1.f, 0.f, visible.y + below_m);
    };
    {
        const FlatCluster c = flatCluster(groundAt(0.01f));
        const auto base = clusterBase(c.segmentation, 1, c.frame);
        ASSERT_TRUE(base);
        EXPECT_NEAR(base->groundDrop_m, 0.01f, 1e-6f);
        EXPECT_NEAR(base->base_m.y, visible.y + 0.01f, 1e-6f);
        EXPECT_NEAR(base->base_m.x, visible.x, 1e-6f);
        EXPECT_NEAR(base->base_m.z, visible.z, 1e-6f);
    }
    for (const float below_m : {RootParams{}.maxGroundDrop_m + 0.01f, -0.01f}) {
        const FlatCluster c = flatCluster(groundAt(below_m));
        const auto base = clusterBase(c.segmentation, 1, c.frame);
        ASSERT_TRUE(base);
        EXPECT_EQ(base->groundDrop_m, 0.f) << "ground " << below_m << " m below";
        EXPECT_NEAR(glm::distance(base->base_m, visible), 0.f, 1e-6f);
    }
}

}  // namespace
}  // namespace meadow::modeling
