// The automatic depth band (capture/src/segmentation/depth_band_mask.cpp) where the tuft shares
// its depths with a wall seen at an angle: every depth of the wall is a stripe across the frame,
// and the histogram's smoothing merges the wall's mode with the tuft's.
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "meadow/capture/segmenter.h"
#include "segmentation/stages.h"

namespace meadow::capture {
namespace {

constexpr int kWidth = 320, kHeight = 240;
constexpr int kWallRows = 100;           // rows 0-99: the wall, 1000 mm at row 99
const cv::Rect kTuft(140, 150, 40, 60);  // the tuft, 960-999 mm
constexpr std::uint16_t kWallNear_mm = 1000, kTuftNear_mm = 960;

// Upright blades 3 px wide, 3 px apart, over `where`, each nearer by `near_mm` + its column
// (the last column holds a blade).
void drawTuft(cv::Mat1w& depth, const cv::Rect& where, std::uint16_t near_mm) {
    for (int x = 0; x < where.width; ++x)
        if (x % 6 >= 3) depth(where).col(x).setTo(near_mm + x);
}

// A wall rising from 1000 mm (its lowest row) by 3 mm a row, nothing below it but the tuft (the
// ground already removed), the tuft's depth changing across its columns.
cv::Mat1w wallBehindTuft() {
    cv::Mat1w depth(kHeight, kWidth, std::uint16_t{0});
    for (int y = 0; y < kWallRows; ++y) depth.row(y).setTo(kWallNear_mm + 3 * (kWallRows - 1 - y));
    drawTuft(depth, kTuft, kTuftNear_mm);
    return depth;
}

Intrinsics intrinsics() {
    Intrinsics k;
    k.width_px = kWidth;
    k.height_px = kHeight;
    k.fx_px = k.fy_px = 288.f;
    k.cx_px = kWidth / 2.f;
    k.cy_px = kHeight / 2.f;
    return k;
}

bool mentions(const StageReport& r, const std::string& text) {
    return std::any_of(r.notes.begin(), r.notes.end(),
                       [&](const std::string& n) { return n.find(text) != std::string::npos; });
}

TEST(DepthBand, ATuftBesideAWallsDepthsIsFoundOnceTheWallsStripesAreLeftOut) {
    const cv::Mat1w depth = wallBehindTuft();
    const cv::Mat1b mask = depth > 0;
    StageReport report;
    const segmentation::DepthBand band = segmentation::automaticDepthBand(
        depth, mask, intrinsics(), SegmenterParams{}, /*groundRemoved=*/true, report);
    ASSERT_TRUE(band.found) << report.notes.back();
    EXPECT_TRUE(mentions(report, "skipped the mode")) << "the merged mode is skipped first";
    EXPECT_TRUE(mentions(report, "looking again without"));
    EXPECT_LE(band.near_m, kTuftNear_mm / 1000.f);
    EXPECT_GE(band.far_m, (kTuftNear_mm + kTuft.width) / 1000.f);
    // The wall's pixels at the band's depths are scenery, the tuft's are not.
    ASSERT_FALSE(band.scenery.empty());
    EXPECT_EQ(cv::countNonZero(band.scenery(kTuft) & (depth(kTuft) > 0)), 0);
    EXPECT_EQ(cv::countNonZero(band.scenery.rowRange(0, kWallRows)), kWallRows * kWidth);
}

TEST(DepthBand, WithoutARemovedGroundTheWallsStripesStay) {
    // Without a plane fit the ground at the tuft's own depths would fill such bins as well, so
    // the second look is not taken: no band.
    const cv::Mat1w depth = wallBehindTuft();
    StageReport report;
    const segmentation::DepthBand band = segmentation::automaticDepthBand(
        depth, depth > 0, intrinsics(), SegmenterParams{}, /*groundRemoved=*/false, report);
    EXPECT_FALSE(band.found);
    EXPECT_FALSE(mentions(report, "looking again without"));
}

TEST(DepthBand, ATuftClearOfTheWallIsFoundAtOnce) {
    cv::Mat1w depth = wallBehindTuft();
    cv::Mat1w tuft = depth(kTuft);
    tuft -= cv::Scalar(200);  // 763-799 mm: its own mode, well in front of the wall
    StageReport report;
    const segmentation::DepthBand band = segmentation::automaticDepthBand(
        depth, depth > 0, intrinsics(), SegmenterParams{}, /*groundRemoved=*/true, report);
    ASSERT_TRUE(band.found);
    EXPECT_FALSE(mentions(report, "looking again without"));
    EXPECT_TRUE(band.scenery.empty());
    EXPECT_LT(band.far_m, kWallNear_mm / 1000.f);
}

// A tuft seen from close up: blades fanning from one base point over three quarters of the
// columns (between an eighth and seven eighths of the width), in front of the wall's stripes.
// It spans more columns than kSceneryColumnCoverage, but it does not reach across the frame as
// the wall does, so it is the tuft (as slim grass seen from 0.6 m is).
TEST(DepthBand, ATuftSeenFromCloseUpIsNotTakenForScenery) {
    cv::Mat1w depth = wallBehindTuft();
    depth(kTuft).setTo(0);
    constexpr std::uint16_t kCloseTuft_mm = 600;
    const cv::Point base(kWidth / 2, kHeight - 10);
    for (int top = kWidth / 8; top <= kWidth * 7 / 8; top += kWidth / 16)
        cv::line(depth, base, {top, kWallRows + 10}, cv::Scalar(kCloseTuft_mm + top / 8), 3);
    float spanned = 0.f;
    {
        cv::Mat1b tuftColumns;
        cv::reduce(depth.rowRange(kWallRows, kHeight) > 0, tuftColumns, 0, cv::REDUCE_MAX);
        spanned = static_cast<float>(cv::countNonZero(tuftColumns)) / kWidth;
    }
    ASSERT_GT(spanned, 0.7f) << "the drawn tuft must span more columns than the scenery test";
    StageReport report;
    const segmentation::DepthBand band = segmentation::automaticDepthBand(
        depth, depth > 0, intrinsics(), SegmenterParams{}, /*groundRemoved=*/true, report);
    ASSERT_TRUE(band.found) << report.notes.back();
    EXPECT_FALSE(mentions(report, "skipped the mode"));
    EXPECT_LE(band.near_m, kCloseTuft_mm / 1000.f);
    EXPECT_GE(band.far_m, (kCloseTuft_mm + kWidth * 7 / 64) / 1000.f);
    EXPECT_LT(band.far_m, kWallNear_mm / 1000.f);
}

// Scenery that ends inside the view (the edge of a ground disc beyond the tuft, a low wall seen
// at an angle) does not reach the side borders, but it fills the rows it covers: still scenery,
// and the tuft behind it is the band (such a ground disc passed for a tuft with --plane none).
// Upright, so the flat-and-level test does not skip it first.
TEST(DepthBand, SceneryEndingInsideTheViewIsStillSkipped) {
    cv::Mat1w depth(kHeight, kWidth, std::uint16_t{0});
    constexpr std::uint16_t kStrip_mm = 700;
    for (int y = 200; y < 216; ++y)
        for (int x = kWidth / 10; x < kWidth * 9 / 10; ++x) depth(y, x) = kStrip_mm + x / 8;
    drawTuft(depth, cv::Rect(kTuft.x, 90, kTuft.width, 80), kTuftNear_mm);
    StageReport report;
    const segmentation::DepthBand band = segmentation::automaticDepthBand(
        depth, depth > 0, intrinsics(), SegmenterParams{}, /*groundRemoved=*/false, report);
    ASSERT_TRUE(band.found) << report.notes.back();
    EXPECT_TRUE(mentions(report, "across the frame")) << "the strip is skipped as scenery";
    EXPECT_GT(band.near_m, (kStrip_mm + kWidth / 8) / 1000.f);
    EXPECT_LE(band.near_m, kTuftNear_mm / 1000.f);
}

}  // namespace
}  // namespace meadow::capture
