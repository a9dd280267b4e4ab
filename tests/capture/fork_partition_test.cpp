// The fork zone (capture/src/segmentation/fork_partition.cpp): below the valleys, where a blade
// in front covers its neighbour's lower part, pixels go to the blade whose continued centre line
// and depth explain them best instead of the wedge split's straight line to the base point.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

#include "meadow/capture/segmenter.h"
#include "support/drawn_tuft.h"

namespace meadow::capture {
namespace {

// Three blades from one base: the middle one in front (1.00 m), upright and wide; the outer two
// behind it (1.03 m) rise along its edges before they lean out, so the valleys where they part
// from it sit far above the base, and the wedges' straight lines from there to the base point
// give the outer blades the middle one's lower part.
drawn::Scene frontAndBack(float middleDepth_m = 1.00f, float outerDepth_m = 1.03f) {
    drawn::Scene s = drawn::fan(1);
    const cv::Point2f base = s.blades[0].base_px;
    drawn::Blade front;
    front.base_px = base;
    front.control_px = base + cv::Point2f(0.f, -90.f);
    front.tip_px = base + cv::Point2f(0.f, -170.f);
    front.baseWidth_px = 16.f;
    front.tipWidth_px = 4.f;
    front.depth_m = middleDepth_m;
    drawn::Blade left = front;
    left.control_px = base + cv::Point2f(-6.f, -110.f);
    left.tip_px = base + cv::Point2f(-90.f, -150.f);
    left.baseWidth_px = 12.f;
    left.tipWidth_px = 2.f;
    left.depth_m = outerDepth_m;
    drawn::Blade right = left;
    right.control_px = base + cv::Point2f(6.f, -110.f);
    right.tip_px = base + cv::Point2f(90.f, -150.f);
    s.blades = {left, front, right};
    return s;
}

// Pixel IoU of each true blade with the found blade that overlaps it most.
std::vector<double> bestIou(const drawn::Drawn& d, const Segmentation& s) {
    std::vector<double> out;
    for (int id = 1; id <= d.bladeCount; ++id) {
        const cv::Mat1b truth = d.labels == id;
        double best = 0.0;
        for (const auto& b : s.blades) {
            const cv::Mat1b found = b.frameMask(d.labels.size());
            const double u = cv::countNonZero(truth | found);
            if (u > 0) best = std::max(best, cv::countNonZero(truth & found) / u);
        }
        out.push_back(best);
    }
    return out;
}

bool noted(const Segmentation& s, const std::string& text) {
    return s.summary().find(text) != std::string::npos;
}

TEST(ForkZone, TheFrontBladeKeepsItsLowerPartThatTheWedgesGaveAway) {
    const auto d = drawn::draw(frontAndBack(), {.sigma_mm = 1.f, .seed = 3});
    SegmenterParams wedgeOnly;
    wedgeOnly.forkByDepth = false;
    const Segmentation before = Segmenter(wedgeOnly).segment(d.frame);
    const Segmentation after = Segmenter().segment(d.frame);
    ASSERT_EQ(before.blades.size(), 3u) << before.summary();
    ASSERT_EQ(after.blades.size(), 3u) << after.summary();
    const auto iouBefore = bestIou(d, before), iouAfter = bestIou(d, after);
    std::cout << "  IoU left " << iouBefore[0] << " -> " << iouAfter[0] << ", front "
              << iouBefore[1] << " -> " << iouAfter[1] << ", right " << iouBefore[2] << " -> "
              << iouAfter[2] << '\n';
    // Every blade gains, the front one most: it gets back the lower part the wedges gave away.
    EXPECT_GT(iouAfter[1], iouBefore[1] + 0.05);
    EXPECT_GT(iouAfter[0], iouBefore[0] + 0.02);
    EXPECT_GT(iouAfter[2], iouBefore[2] + 0.02);
    EXPECT_TRUE(noted(after, "fork zone:")) << after.summary();
    EXPECT_FALSE(noted(before, "fork zone:")) << before.summary();
}

// The same blades with the outer two in front: now they cover the middle one's lower part. The
// drawn outlines are the same, so only depth can tell the two apart; the middle blade keeps its
// lower part in the one and not in the other.
TEST(ForkZone, DepthDecidesWhichBladeIsInFront) {
    const auto middleArea = [](float middleDepth_m, float outerDepth_m, bool fork) {
        const auto d =
            drawn::draw(frontAndBack(middleDepth_m, outerDepth_m), {.sigma_mm = 1.f, .seed = 3});
        SegmenterParams p;
        p.forkByDepth = fork;
        const Segmentation s = Segmenter(p).segment(d.frame);
        const cv::Mat1b middle = d.labels == 2;  // the found blade that holds most of it
        int area = 0, most = 0;
        for (const auto& b : s.blades) {
            const cv::Mat1b found = b.frameMask(d.labels.size());
            if (const int overlap = cv::countNonZero(middle & found); overlap > most)
                most = overlap, area = cv::countNonZero(found);
        }
        return area;
    };
    const int inFront = middleArea(1.00f, 1.03f, true), behind = middleArea(1.03f, 1.00f, true);
    const int wedgeFront = middleArea(1.00f, 1.03f, false);
    const int wedgeBehind = middleArea(1.03f, 1.00f, false);
    std::cout << "  middle blade: " << inFront << " px in front, " << behind
              << " px behind (wedges: " << wedgeFront << " / " << wedgeBehind << ")\n";
    EXPECT_LE(std::abs(wedgeFront - wedgeBehind), wedgeFront / 50);  // geometry alone: alike
    EXPECT_GT(inFront, behind + behind / 5);
}

// A given mask has no depth to tell which blade is in front: the wedges stand.
TEST(ForkZone, AMaskWithoutDepthKeepsTheWedgeSplit) {
    const auto d = drawn::draw(frontAndBack());
    const Segmentation s = Segmenter().segmentMask(d.labels > 0);
    ASSERT_EQ(s.blades.size(), 3u) << s.summary();
    EXPECT_FALSE(noted(s, "fork zone:")) << s.summary();
}

// Blades under 4 px wide at their fork keep their wedges: a pixel of centre-line error is a
// whole half width there.
TEST(ForkZone, NarrowBladesKeepTheirWedges) {
    const auto scene = drawn::fan(5, 60.f, 160.f, /*baseWidth_px=*/3.f);
    const auto d = drawn::draw(scene, {.sigma_mm = 1.f, .seed = 4});
    SegmenterParams wedgeOnly;
    wedgeOnly.forkByDepth = false;
    const Segmentation before = Segmenter(wedgeOnly).segment(d.frame);
    const Segmentation after = Segmenter().segment(d.frame);
    ASSERT_EQ(before.blades.size(), after.blades.size());
    for (size_t i = 0; i < after.blades.size(); ++i)
        EXPECT_EQ(cv::countNonZero(before.blades[i].frameMask(d.labels.size()) !=
                                   after.blades[i].frameMask(d.labels.size())),
                  0)
            << "blade " << i;
    EXPECT_TRUE(noted(after, "fork zone: 0 px")) << after.summary();
}

TEST(ForkZone, ParametersOutOfRangeAreRefused) {
    SegmenterParams p;
    p.forkDepthSigma_mm = 0.f;
    EXPECT_NE(p.problem().find("forkDepthSigma_mm"), std::string::npos);
    p = {};
    p.forkMaxRaggedness = -0.1f;
    EXPECT_NE(p.problem().find("forkMaxRaggedness"), std::string::npos);
}

}  // namespace
}  // namespace meadow::capture
