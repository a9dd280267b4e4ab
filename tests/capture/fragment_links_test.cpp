// Thin fragments joined back (capture/src/segmentation/fragment_links.cpp): a blade under ~3 px
// wide that the sensor broke comes out of the clean-up as a stalk and fragments; a fragment is
// joined to what lies past one of its ends along its axis, and to nothing else.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "meadow/capture/segmenter.h"

namespace meadow::capture {
namespace {

// A 3 px wide blade from (320, 420) up to (330, 200), with rows [gapTop, gapBottom) cut out.
cv::Mat1b brokenBlade(int gapTop, int gapBottom) {
    cv::Mat1b mask(480, 640, std::uint8_t{0});
    cv::line(mask, {320, 420}, {330, 200}, 255, 3, cv::LINE_8);
    mask.rowRange(gapTop, gapBottom).setTo(0);
    return mask;
}

Segmentation segment(const cv::Mat1b& mask, float gap_px = SegmenterParams{}.fragmentLinkGap_px) {
    SegmenterParams p;
    p.fragmentLinkGap_px = gap_px;
    return Segmenter(p).segmentMask(mask);
}

bool noted(const Segmentation& s) {
    return s.summary().find("end(s) of thin fragments") != std::string::npos;
}

TEST(FragmentLinks, ABrokenThinBladeIsOneBladeAgain) {
    const cv::Mat1b mask = brokenBlade(300, 306);  // a 6 px gap
    const Segmentation off = segment(mask, 0.f);
    const Segmentation on = segment(mask);
    EXPECT_EQ(off.clusters.size(), 2u) << off.summary();
    ASSERT_EQ(on.clusters.size(), 1u) << on.summary();
    ASSERT_EQ(on.blades.size(), 1u) << on.summary();
    // The blade holds both parts and the gap between them.
    const cv::Mat1b blade = on.blades[0].frameMask(mask.size());
    EXPECT_EQ(cv::countNonZero(mask & ~blade), 0);
    EXPECT_GT(cv::countNonZero(blade.rowRange(300, 306)), 0);
    EXPECT_TRUE(noted(on)) << on.summary();
    EXPECT_FALSE(noted(off)) << off.summary();
}

TEST(FragmentLinks, AGapWiderThanTheReachStaysOpen) {
    const Segmentation s = segment(brokenBlade(300, 312));  // 12 px > 10 px
    EXPECT_EQ(s.clusters.size(), 2u) << s.summary();
    EXPECT_FALSE(noted(s)) << s.summary();
}

// A fragment lying beside a blade, not past its end, is left apart: neither points at the other.
TEST(FragmentLinks, AFragmentBesideABladeIsNotJoinedToIt) {
    cv::Mat1b mask(480, 640, std::uint8_t{0});
    cv::rectangle(mask, {319, 220}, {321, 420}, 255, cv::FILLED);
    cv::rectangle(mask, {327, 320}, {329, 400}, 255, cv::FILLED);  // 5 px of background between
    const Segmentation s = segment(mask);
    EXPECT_EQ(s.clusters.size(), 2u) << s.summary();
    EXPECT_FALSE(noted(s)) << s.summary();
}

// Parts larger than fragmentMaxArea_px (a tuft, a leaf) are no fragments: two leaves end to end
// with a 6 px gap stay two.
TEST(FragmentLinks, LargePartsAreNotFragments) {
    cv::Mat1b mask(480, 640, std::uint8_t{0});
    cv::rectangle(mask, {316, 310}, {324, 420}, 255, cv::FILLED);  // 999 px each
    cv::rectangle(mask, {316, 193}, {324, 303}, 255, cv::FILLED);  // 6 px gap
    const Segmentation s = segment(mask);
    EXPECT_EQ(s.clusters.size(), 2u) << s.summary();
    EXPECT_FALSE(noted(s)) << s.summary();
}

TEST(FragmentLinks, ParametersOutOfRangeAreRefused) {
    SegmenterParams p;
    p.fragmentLinkAngle_deg = 120.f;
    EXPECT_NE(p.problem().find("fragmentLinkAngle_deg"), std::string::npos);
    p = {};
    p.fragmentMinAspect = 0.5f;
    EXPECT_NE(p.problem().find("fragmentMinAspect"), std::string::npos);
}

}  // namespace
}  // namespace meadow::capture
