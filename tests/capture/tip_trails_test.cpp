// Tip trails (capture/src/segmentation/tip_trails.cpp): dotted in-band readings that run on
// from the cleaned mask, as a tip under two pixels wide reaches a structured-light sensor, are
// linked back; edge speckle, surfaces and readings past a gap are not.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "meadow/capture/error.h"
#include "meadow/capture/segmenter.h"
#include "segmentation/stages.h"

namespace meadow::capture {
namespace {

namespace seg = segmentation;

const cv::Size kFrame{160, 200};
constexpr std::uint16_t kWall_mm = 1500;
// The cleaned mask: an upright blade 8 px wide, rows 80-179, base at the bottom, narrowing over
// its top 20 rows to a 2 px end at row 80 (columns 79-80), where its tip falls apart.
const cv::Rect kBlade{76, 80, 8, 100};
constexpr int kColumn = 79;  // the dotted tip's column, on the narrow end

cv::Mat1b bladeMask() {
    cv::Mat1b m = cv::Mat1b::zeros(kFrame);
    m(cv::Rect(kBlade.x, kBlade.y + 20, kBlade.width, kBlade.height - 20)).setTo(255);
    const std::vector<cv::Point> taper{{kBlade.x, kBlade.y + 20},
                                       {kColumn, kBlade.y},
                                       {kColumn + 1, kBlade.y},
                                       {kBlade.br().x - 1, kBlade.y + 20}};
    cv::fillConvexPoly(m, taper, 255);
    return m;
}

// Every second row from just above the blade up to `top` (a tip under lateral noise keeps
// about half of its readings).
void dotTip(cv::Mat1b& readings, int top, int column = kColumn) {
    for (int y = kBlade.y - 2; y >= top; y -= 2) readings(y, column) = 255;
}

// The pixels 2-3 px outside `mask` (chessboard distance), where lateral noise leaves speckle.
cv::Mat1b ringAround(const cv::Mat1b& mask) {
    cv::Mat1b ring, inner;
    cv::dilate(mask, ring, cv::getStructuringElement(cv::MORPH_RECT, {7, 7}));
    cv::dilate(mask, inner, cv::Mat());
    return ring & ~inner;
}

// 4-connected background regions that touch no side of the frame.
int enclosedHoles(const cv::Mat1b& mask) {
    cv::Mat1i labels;
    cv::Mat stats, centroids;
    const int n = cv::connectedComponentsWithStats(mask == 0, labels, stats, centroids, 4, CV_32S);
    int holes = 0;
    for (int i = 1; i < n; ++i) {
        const int x = stats.at<int>(i, cv::CC_STAT_LEFT), y = stats.at<int>(i, cv::CC_STAT_TOP);
        const int w = stats.at<int>(i, cv::CC_STAT_WIDTH), h = stats.at<int>(i, cv::CC_STAT_HEIGHT);
        holes += x > 0 && y > 0 && x + w < mask.cols && y + h < mask.rows;
    }
    return holes;
}

// Runs the stage on the blade with `readings` and expects it to leave the mask as it is and to
// say why in a note containing `why`.
void expectNotFollowed(const cv::Mat1b& readings, const std::string& why) {
    cv::Mat1b mask = bladeMask();
    const cv::Mat1b before = mask.clone();
    StageReport report;
    const seg::TipTrails trails = seg::recoverTipTrails(readings, cv::Mat1b(), {}, mask, report);
    EXPECT_TRUE(trails.added.empty());
    EXPECT_EQ(cv::countNonZero(mask != before), 0);
    bool toldWhy = false;
    for (const auto& note : report.notes) toldWhy |= note.find(why) != std::string::npos;
    EXPECT_TRUE(toldWhy) << "no note says '" << why << "'";
}

TEST(TipTrails, DottedReadingsPastTheTipAreLinkedBackOnePixelWide) {
    cv::Mat1b mask = bladeMask();
    cv::Mat1b readings = mask.clone();
    dotTip(readings, 40);  // 40 px of dotted tip above row 80
    StageReport report;
    const seg::TipTrails trails = seg::recoverTipTrails(readings, cv::Mat1b(), {}, mask, report);
    // The blade now reaches the top dot, through one connected line of one pixel.
    EXPECT_TRUE(trails.holds({kColumn, 40}));
    EXPECT_EQ(mask(40, kColumn), 255);
    for (int y = 40; y < kBlade.y; ++y) EXPECT_EQ(cv::countNonZero(mask.row(y)), 1) << "row " << y;
    cv::Mat1i labels;
    EXPECT_EQ(cv::connectedComponents(mask, labels, 8), 2);  // background + one region
    EXPECT_EQ(enclosedHoles(mask), 0);
    ASSERT_FALSE(report.notes.empty());
    EXPECT_NE(report.notes.back().find("1 tip trail"), std::string::npos) << report.notes.back();
}

// Two tips whose dotted readings a chain of readings joins above them (as readings recurring
// over many frames join neighbouring tips): one group of readings, two trails, each linked back
// onto its own blade where it leaves it.
TEST(TipTrails, TwoTipsJoinedByReadingsBetweenThemAreTwoTrails) {
    constexpr int kShift = 30;  // the second blade, kShift px to the right of the first
    cv::Mat1b mask = bladeMask();
    cv::Mat1b second;
    cv::warpAffine(mask, second, cv::Matx23f(1, 0, kShift, 0, 1, 0), mask.size());
    mask |= second;
    cv::Mat1b readings = mask.clone();
    constexpr int kTop = 60;
    dotTip(readings, kTop);
    dotTip(readings, kTop, kColumn + kShift);
    for (int x = kColumn + 2; x < kColumn + kShift; x += 2) readings(kTop - 2, x) = 255;
    StageReport report;
    const seg::TipTrails trails = seg::recoverTipTrails(readings, cv::Mat1b(), {}, mask, report);
    for (const int column : {kColumn, kColumn + kShift}) {
        EXPECT_TRUE(trails.holds({column, kTop})) << "column " << column;
        EXPECT_EQ(mask(kBlade.y - 1, column), 255) << "column " << column << ": not linked back";
    }
    ASSERT_FALSE(report.notes.empty());
    EXPECT_NE(report.notes.back().find("2 tip trail"), std::string::npos) << report.notes.back();
}

TEST(TipTrails, EdgeSpeckleBesideTheBladeIsNotATrail) {
    cv::Mat1b readings = bladeMask();
    // Readings the lateral noise scattered 2-3 px off both sides, every eighth row (about 6 %
    // of the pixels there: nominal noise).
    for (int y = kBlade.y + 22; y < kBlade.br().y - 2; y += 8) {
        readings(y, kBlade.x - 2 - (y % 2)) = 255;
        readings(y, kBlade.br().x + 1 + (y % 2)) = 255;
    }
    expectNotFollowed(readings, "edge noise");
}

TEST(TipTrails, ASurfaceOfReadingsBesideTheBladeIsNotFollowed) {
    cv::Mat1b readings = bladeMask();
    // A 40 x 40 checkerboard of readings touching the blade's side: a leaf or ground behind,
    // far more readings than a line of the longest trail holds.
    for (int y = 100; y < 140; ++y)
        for (int x = kBlade.br().x + 1; x < kBlade.br().x + 41; ++x)
            if ((x + y) % 2 == 0) readings(y, x) = 255;
    expectNotFollowed(readings, "too wide");
}

TEST(TipTrails, ReadingsPastAGapWiderThanTipTrailGapAreLeftOut) {
    cv::Mat1b mask = bladeMask();
    cv::Mat1b readings = mask.clone();
    dotTip(readings, 60);                                          // rows 78..60
    for (int y = 54; y >= 30; y -= 2) readings(y, kColumn) = 255;  // past a 5-row gap
    SegmenterParams params;
    ASSERT_LT(params.tipTrailGap_px, 5);
    StageReport report;
    const seg::TipTrails trails =
        seg::recoverTipTrails(readings, cv::Mat1b(), params, mask, report);
    EXPECT_TRUE(trails.holds({kColumn, 60}));
    EXPECT_EQ(cv::countNonZero(mask.rowRange(0, 58)), 0);
}

TEST(TipTrails, ReadingsRecurringOverMoreFramesBridgeTheGapsOfThisFramesOwn) {
    cv::Mat1b mask = bladeMask();
    cv::Mat1b readings = mask.clone();
    dotTip(readings, 60);                                          // rows 78..60
    for (int y = 54; y >= 34; y -= 2) readings(y, kColumn) = 255;  // past a 5-row gap
    // Readings recurring over a dozen frames fill the gap (every second row, as the tip reads).
    cv::Mat1b recurring = cv::Mat1b::zeros(kFrame);
    for (int y = 58; y >= 56; y -= 2) recurring(y, kColumn) = 255;
    StageReport report;
    const seg::TipTrails trails = seg::recoverTipTrails(readings, recurring, {}, mask, report);
    EXPECT_TRUE(trails.holds({kColumn, 34}));
    EXPECT_EQ(mask(34, kColumn), 255);
    EXPECT_EQ(cv::countNonZero(mask.rowRange(0, 34)), 0);
}

TEST(TipTrails, HowRaggedTheEdgesAreIsMeasuredOnThisFramesOwnReadings) {
    cv::Mat1b mask = bladeMask();
    cv::Mat1b readings = mask.clone();
    dotTip(readings, 40);
    // Recurring readings all around the blade, 2-3 px out: they would read as far too ragged.
    const cv::Mat1b ring = ringAround(mask);
    StageReport alone, withRing;
    cv::Mat1b maskAlone = mask.clone();
    const seg::TipTrails own = seg::recoverTipTrails(readings, cv::Mat1b(), {}, maskAlone, alone);
    const seg::TipTrails both = seg::recoverTipTrails(readings, ring, {}, mask, withRing);
    EXPECT_FLOAT_EQ(both.raggedness, own.raggedness);
    EXPECT_LT(both.raggedness, SegmenterParams{}.tipTrailMaxRaggedness);
}

TEST(TipTrails, ReadingsThatRunAlongTheBladesSideAreNotATip) {
    cv::Mat1b readings = bladeMask();
    // A chain of readings 3 px off the blade's right side, rows 170 up to 110: speckle that
    // lateral noise strung along a side reaches as far from the mask as a tip does, but leaves
    // it sideways.
    const int column = kBlade.br().x + 2;
    for (int y = 170; y >= 110; y -= 2) readings(y, column) = 255;
    for (int x = column; x <= column + 8; x += 2) readings(110, x) = 255;  // and away from it
    expectNotFollowed(readings, "sideways");
}

TEST(TipTrails, ATrailThatBendsBesideItsBladeEnclosesNoHole) {
    cv::Mat1b mask = bladeMask();
    cv::Mat1b readings = mask.clone();
    // A tip bent over: its dotted readings leave the narrow end upward, then turn and come
    // back down 4 px beside the taper.
    for (int y = kBlade.y - 2; y >= kBlade.y - 10; y -= 2) readings(y, kColumn) = 255;
    for (int x = kColumn + 2; x <= kColumn + 8; x += 2) readings(kBlade.y - 11, x) = 255;
    for (int y = kBlade.y - 9; y <= kBlade.y + 6; y += 2) readings(y, kColumn + 9) = 255;
    StageReport report;
    const seg::TipTrails trails = seg::recoverTipTrails(readings, cv::Mat1b(), {}, mask, report);
    EXPECT_TRUE(trails.holds({kColumn, kBlade.y - 10}));
    EXPECT_EQ(enclosedHoles(mask), 0);
}

TEST(TipTrails, NotFollowedWhereEdgesAreTooRagged) {
    cv::Mat1b mask = bladeMask();
    cv::Mat1b readings = mask.clone();
    dotTip(readings, 40);
    // Readings on every third pixel 2-3 px outside the blade: noise far above nominal.
    const cv::Mat1b ring = ringAround(mask);
    int k = 0;
    for (int y = 0; y < ring.rows; ++y)
        for (int x = 0; x < ring.cols; ++x)
            if (ring(y, x) && k++ % 3 == 0) readings(y, x) = 255;
    expectNotFollowed(readings, "too ragged");
}

TEST(TipTrails, SegmenterFollowsADottedTipAndSaysSo) {
    // Depth: the blade at 0.8 m with its dotted tip, a wall at 1.5 m; a user band keeps the
    // blade. Outlier removal drops the dots (too few neighbours), the trail brings them back.
    DepthFrame frame;
    frame.intrinsics.width_px = kFrame.width;
    frame.intrinsics.height_px = kFrame.height;
    frame.intrinsics.cx_px = 79.5f;
    frame.intrinsics.cy_px = 99.5f;
    frame.depth_mm = cv::Mat1w(kFrame, kWall_mm);
    cv::Mat1b blade = bladeMask();
    dotTip(blade, 40);
    frame.depth_mm.setTo(800, blade);
    SegmenterParams params;
    params.nearDepth_m = 0.7f;
    params.farDepth_m = 0.9f;
    params.planeMethod = PlaneMethod::None;
    const Segmentation found = Segmenter(params).segment(frame);
    ASSERT_EQ(found.blades.size(), 1u) << found.summary();
    const BladeContour& b = found.blades.front();
    EXPECT_TRUE(b.tipOnTrail);
    EXPECT_LE(b.contour_px[static_cast<size_t>(b.tipIndex)].y, 41) << found.summary();
    EXPECT_NEAR(found.tuftNearest_m, 0.8f, 1e-3f);
    EXPECT_NEAR(found.tuftFarthest_m, 0.8f, 1e-3f);

    // Readings that recur over more frames carry the trail past this frame's last dot.
    RecurringReadings tips;
    tips.frames = 12;
    tips.depth_mm = cv::Mat1w(kFrame, kWall_mm);
    // (Up to row 34: a trail reaches at most tipTrailMaxLength_px, 48, past the mask's box.)
    for (int y = 39; y >= 34; --y) tips.depth_mm(y, kColumn) = 801;
    const Segmentation longer = Segmenter(params).segment(std::span(&frame, 1), tips);
    ASSERT_EQ(longer.blades.size(), 1u) << longer.summary();
    EXPECT_EQ(longer.recurringFrames, 12);
    EXPECT_NE(longer.summary().find("px of in-band readings that recur over 12 frames"),
              std::string::npos)
        << longer.summary();
    EXPECT_EQ(found.recurringFrames, 0);
    const BladeContour& l = longer.blades.front();
    EXPECT_TRUE(l.tipOnTrail);
    EXPECT_LE(l.contour_px[static_cast<size_t>(l.tipIndex)].y, 35) << longer.summary();
    tips.depth_mm = cv::Mat1w(kFrame.height + 1, kFrame.width, kWall_mm);
    EXPECT_THROW((void)Segmenter(params).segment(std::span(&frame, 1), tips), CaptureError);

    params.tipTrailMinReach_px = 0.f;  // off: the blade ends at the cleaned mask
    const Segmentation cut = Segmenter(params).segment(frame);
    ASSERT_EQ(cut.blades.size(), 1u) << cut.summary();
    const BladeContour& c = cut.blades.front();
    EXPECT_FALSE(c.tipOnTrail);
    EXPECT_GE(c.contour_px[static_cast<size_t>(c.tipIndex)].y, kBlade.y - 2) << cut.summary();
}

}  // namespace
}  // namespace meadow::capture
