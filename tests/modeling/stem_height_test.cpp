// The stem's height (modeling/src/stem_height.cpp): its line's ends back-projected at the depth
// read around them, the tallest of a segmentation's stems, the median over segmentations.
#include "meadow/modeling/stem_height.h"

#include <gtest/gtest.h>

namespace meadow::modeling {
namespace {

constexpr std::uint16_t kDepth_mm = 1000;

capture::DepthFrame flatFrame() {
    capture::DepthFrame frame;
    frame.intrinsics = capture::Intrinsics::kinectV1();
    frame.depth_mm = cv::Mat1w(480, 640, kDepth_mm);
    return frame;
}

capture::BladeCluster clusterWithStem(cv::Point foot, cv::Point top) {
    capture::BladeCluster c;
    c.stemLine_px = {foot, (foot + top) / 2, top};
    return c;
}

TEST(StemHeight, IsTheDistanceFromFootToTopAtTheirDepth) {
    const capture::DepthFrame frame = flatFrame();
    capture::Segmentation seg;
    seg.clusters.push_back(clusterWithStem({320, 400}, {320, 200}));
    const auto height = stemHeight_m(seg, frame);
    ASSERT_TRUE(height);
    const float expected = 200.f * (kDepth_mm / 1000.f) / frame.intrinsics.fy_px;  // 0.38 m
    EXPECT_NEAR(*height, expected, 1e-4f);
}

TEST(StemHeight, TheTallestStemCountsAndOneWithoutReadingsAtAnEndDoesNot) {
    capture::DepthFrame frame = flatFrame();
    frame.depth_mm(cv::Rect(300, 0, 40, 120)).setTo(0);  // no readings round (320, 50)
    capture::Segmentation seg;
    seg.clusters.push_back(clusterWithStem({320, 400}, {320, 50}));   // its top unread
    seg.clusters.push_back(clusterWithStem({100, 400}, {100, 300}));  // 100 px
    seg.clusters.push_back(capture::BladeCluster{});                  // no stem
    seg.clusters.push_back(clusterWithStem({500, 400}, {500, 250}));  // 150 px: the tallest
    const auto height = stemHeight_m(seg, frame);
    ASSERT_TRUE(height);
    EXPECT_NEAR(*height, 150.f / frame.intrinsics.fy_px, 1e-4f);
}

TEST(StemHeight, NoStemNoHeight) {
    capture::Segmentation seg;
    seg.clusters.push_back(capture::BladeCluster{});
    EXPECT_FALSE(stemHeight_m(seg, flatFrame()));
    EXPECT_FALSE(stemOf({}));
}

TEST(StemHeight, TheLibrarysStemIsTheMedianOfItsViews) {
    const auto stem = stemOf({0.5f, 0.9f, 0.55f, 0.1f, 0.6f});
    ASSERT_TRUE(stem);
    EXPECT_EQ(stem->height_m, 0.55f);
    EXPECT_EQ(stem->views, 5);
}

}  // namespace
}  // namespace meadow::modeling
