// The shape of an object's parts (capture/src/segmentation/part_shape.cpp): how wide and how
// elongated they are, its thick base (a pot), and whether it looks like a plant's leaves. Drawn
// at 1 m before the Kinect v1 intrinsics, where a pixel is 1.74 mm.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "meadow/capture/intrinsics.h"
#include "meadow/capture/segmenter.h"
#include "segmentation/stages.h"

namespace meadow::capture {
namespace {

namespace seg = segmentation;

const cv::Size kFrame{320, 320};
constexpr float kDepth_m = 1.0f;
const Intrinsics kIntrinsics = Intrinsics::kinectV1();

float metres(float px) { return px * kDepth_m / kIntrinsics.fx_px; }

cv::Mat1w depthOf(const cv::Mat1b& mask) {
    cv::Mat1w depth = cv::Mat1w::zeros(mask.size());
    depth.setTo(static_cast<std::uint16_t>(kDepth_m * 1000.f), mask);
    return depth;
}

// `n` upright blades 10 px (1.7 cm) wide and `length` px long, 20 px apart, their bases on row
// `baseRow`.
cv::Mat1b blades(int n, int length, int baseRow) {
    cv::Mat1b m = cv::Mat1b::zeros(kFrame);
    for (int i = 0; i < n; ++i) m(cv::Rect(60 + 20 * i, baseRow - length, 10, length)).setTo(255);
    return m;
}

// A pot 80 px (14 cm) wide and 70 px tall standing on row 300.
const cv::Rect kPot{100, 230, 80, 70};

std::string unlikeLeaves(const cv::Mat1b& mask) {
    return seg::unlikeLeaves(mask, depthOf(mask), kIntrinsics, SegmenterParams{});
}

TEST(PartShape, AStripIsHalfItsWidthWideAndAsElongatedAsItIsLongOverWide) {
    cv::Mat1b strip = cv::Mat1b::zeros(kFrame);
    strip(cv::Rect(150, 50, 10, 200)).setTo(255);
    const seg::PartShape shape = seg::partShape(strip, kDepth_m, kIntrinsics, false);
    EXPECT_NEAR(shape.width_m, metres(5.f), 0.25 * metres(5.f));
    EXPECT_NEAR(shape.elongation, 20.f, 5.f);
}

TEST(PartShape, HolesOfASolidSurfaceAreFilledButTheGapsBetweenBladesAreNot) {
    cv::Mat1b riddled = cv::Mat1b::zeros(kFrame);
    riddled(cv::Rect(40, 40, 200, 150)).setTo(255);
    for (int y = 46; y < 185; y += 12)
        for (int x = 46; x < 235; x += 12) riddled(cv::Rect(x, y, 3, 3)).setTo(0);
    const float filled = seg::partShape(riddled, kDepth_m, kIntrinsics, true).width_m;
    const float asRead = seg::partShape(riddled, kDepth_m, kIntrinsics, false).width_m;
    EXPECT_GT(filled, 0.04f);  // a quarter of its 26 cm height
    EXPECT_LT(asRead, 0.02f);  // the holes make it look like a net of thin parts
    const cv::Mat1b fan = blades(6, 200, 250);
    EXPECT_NEAR(seg::partShape(fan, kDepth_m, kIntrinsics, true).width_m, metres(5.f),
                0.25 * metres(5.f));
}

TEST(PartShape, BladesAreLeaves) { EXPECT_EQ(unlikeLeaves(blades(6, 200, 250)), ""); }

TEST(PartShape, BladesGrowingOutOfAPotAreLeavesAndThePotIsItsThickBase) {
    cv::Mat1b plant = blades(5, 180, kPot.y + 5);
    plant(kPot).setTo(255);
    EXPECT_EQ(unlikeLeaves(plant), "");
    const cv::Mat1b base = seg::thickBase(plant, kDepth_m, kIntrinsics);
    EXPECT_GE(cv::countNonZero(base(kPot)), 0.9 * kPot.area());
    const cv::Rect aboveThePot(0, 0, kFrame.width, kPot.y - 3);
    EXPECT_EQ(cv::countNonZero(base(aboveThePot)), 0);
}

TEST(PartShape, APotAloneIsThickThroughout) {
    cv::Mat1b pot = cv::Mat1b::zeros(kFrame);
    pot(kPot).setTo(255);
    EXPECT_NE(unlikeLeaves(pot).find("thick throughout"), std::string::npos) << unlikeLeaves(pot);
}

TEST(PartShape, ATableIsTooWide) {
    cv::Mat1b table = cv::Mat1b::zeros(kFrame);
    table(cv::Rect(20, 20, 280, 70)).setTo(255);  // a top 49 x 12 cm
    table(cv::Rect(30, 90, 10, 150)).setTo(255);  // on legs 1.7 cm thick
    table(cv::Rect(280, 90, 10, 150)).setTo(255);
    EXPECT_NE(unlikeLeaves(table).find("cm wide"), std::string::npos) << unlikeLeaves(table);
}

// A grown maize shoot's leaves (7-13 cm across) measure wider than a grass's, but the plant's
// parts are many times longer over their width (22-115 on the plant bench) than a table's on
// its legs (about 9) or a board's: up to half as wide again as the limit, that length decides.
TEST(PartShape, BroadPartsAreLeavesOnlyWhenTheyAreLong) {
    const SegmenterParams params;
    const float broad = 1.3f * params.plantMaxMeanWidth_m;
    EXPECT_EQ(seg::unlikeLeafParts({broad, 30.f}, params), "");
    EXPECT_NE(seg::unlikeLeafParts({broad, 9.f}, params).find("cm wide and 9 times as long"),
              std::string::npos)
        << seg::unlikeLeafParts({broad, 9.f}, params);
    EXPECT_NE(
        seg::unlikeLeafParts({1.6f * params.plantMaxMeanWidth_m, 100.f}, params).find("cm wide"),
        std::string::npos);
    EXPECT_EQ(seg::unlikeLeafParts({0.9f * params.plantMaxMeanWidth_m, 9.f}, params), "");
}

// A tray of lettuce seen from above: six heads 13 cm across apart from each other, each a
// rosette of eight broad leaves (ellipses 7 x 4.9 cm, their centres 3 cm out) that overlap
// into a lobed disc. Taken together their lengths add up to a long strip's; each is round.
TEST(PartShape, ATrayOfLettuceFromAboveIsNotLeaves) {
    cv::Mat1b tray = cv::Mat1b::zeros(kFrame);
    for (int row = 0; row < 2; ++row)
        for (int col = 0; col < 3; ++col) {
            const cv::Point centre(60 + 100 * col, 90 + 130 * row);
            for (int leaf = 0; leaf < 8; ++leaf) {
                const double angle = 45.0 * leaf;
                const cv::Point offset(static_cast<int>(17 * std::cos(angle * CV_PI / 180)),
                                       static_cast<int>(17 * std::sin(angle * CV_PI / 180)));
                cv::ellipse(tray, centre + offset, {20, 14}, angle, 0, 360, 255, cv::FILLED);
            }
        }
    EXPECT_NE(unlikeLeaves(tray), "");
    const seg::PartShape shape = seg::partShape(tray, kDepth_m, kIntrinsics, true);
    EXPECT_LT(shape.elongation, seg::kMinLeafElongation);
}

TEST(PartShape, AShortEdgeIsNotElongatedEnough) {
    cv::Mat1b edge = cv::Mat1b::zeros(kFrame);
    edge(cv::Rect(150, 100, 14, 60)).setTo(255);  // 2.4 x 10 cm: a door edge, a chair's leg
    EXPECT_NE(unlikeLeaves(edge).find("times as long as it is wide"), std::string::npos)
        << unlikeLeaves(edge);
}

TEST(PartShape, AnEmptyMaskHasNoShape) {
    const cv::Mat1b none = cv::Mat1b::zeros(kFrame);
    EXPECT_EQ(seg::partShape(none, kDepth_m, kIntrinsics, true).width_m, 0.f);
    EXPECT_EQ(cv::countNonZero(seg::thickBase(none, kDepth_m, kIntrinsics)), 0);
}

}  // namespace
}  // namespace meadow::capture
