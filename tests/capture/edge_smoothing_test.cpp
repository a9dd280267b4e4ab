// Edge smoothing along the contour (capture/src/segmentation/contour_smoothing.cpp): an exact
// mask comes back as it was, an edge ragged as the sensor's lateral noise leaves it comes back
// closer to the truth, and holes, gaps, thin lines and tips are kept.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "meadow/capture/segmenter.h"
#include "segmentation/stages.h"

namespace meadow::capture {
namespace {

constexpr float kSigma = 4.f;     // the default, SegmenterParams::edgeSmoothingSigma_px
constexpr float kMaxShift = 1.f;  // SegmenterParams::edgeSmoothingMaxShift_px

// A blade-like ellipse (semi-axes 60 x 6 px) at `angle_deg`, rasterised as the sensor sees it:
// a pixel belongs to the shape when its centre does.
cv::Mat1b ellipse(float angle_deg) {
    cv::Mat1b m = cv::Mat1b::zeros(200, 200);
    const float a = angle_deg * std::numbers::pi_v<float> / 180.f;
    for (int y = 0; y < m.rows; ++y)
        for (int x = 0; x < m.cols; ++x) {
            const float dx = static_cast<float>(x) - 100.3f, dy = static_cast<float>(y) - 100.7f;
            const float u = dx * std::cos(a) + dy * std::sin(a),
                        v = -dx * std::sin(a) + dy * std::cos(a);
            if (u * u / 3600.f + v * v / 36.f <= 1.f) m(y, x) = 255;
        }
    return m;
}

// The simulator's lateral noise: each pixel reads the truth at a point N(0, 0.8 px) away.
cv::Mat1b lateralNoise(const cv::Mat1b& truth, std::uint64_t seed) {
    cv::RNG rng(seed);
    cv::Mat1b out = truth.clone();
    for (int y = 1; y + 1 < truth.rows; ++y)
        for (int x = 1; x + 1 < truth.cols; ++x) {
            const int sx = std::clamp(x + cvRound(rng.gaussian(0.8)), 0, truth.cols - 1);
            const int sy = std::clamp(y + cvRound(rng.gaussian(0.8)), 0, truth.rows - 1);
            out(y, x) = truth(sy, sx);
        }
    return out;
}

cv::Mat1b smoothed(const cv::Mat1b& mask) {
    cv::Mat1b out = mask.clone();
    StageReport report;
    segmentation::smoothContours(out, kSigma, kMaxShift, report);
    return out;
}

int components(const cv::Mat1b& mask, int connectivity) {
    cv::Mat1i labels;
    return cv::connectedComponents(mask, labels, connectivity) - 1;
}

TEST(EdgeSmoothing, ExactShapesComeBackAsTheyWere) {
    // Straight and slanted edges alike: the half-pixel from a boundary pixel's centre to the
    // edge is taken along the pixel grid. Only a few pixels at the two ends may change (more
    // when the ends are averaged like the sides).
    for (float angle : {0.f, 20.f, 45.f, 70.f}) {
        const cv::Mat1b truth = ellipse(angle);
        const int changed = cv::countNonZero(smoothed(truth) ^ truth);
        EXPECT_LE(changed, 12) << angle << " deg, of " << cv::countNonZero(truth);
    }
}

// The clean-up stage (closing, smoothing, speckle and small holes) with edge smoothing at sigma.
cv::Mat1b cleanedUp(const cv::Mat1b& mask, float sigma) {
    SegmenterParams p;
    p.edgeSmoothingSigma_px = sigma;
    cv::Mat1b out = mask.clone();
    StageReport report;
    segmentation::cleanUpMask(p, out, report);
    return out;
}

TEST(EdgeSmoothing, RaggedEdgeComesBackCloserToTheTruth) {
    // Over 4 angles x 3 seeds, edge smoothing must leave clearly fewer pixels wrong than the
    // clean-up alone, on each and in all.
    int rawTotal = 0, fixedTotal = 0;
    for (float angle : {0.f, 20.f, 45.f, 70.f})
        for (std::uint64_t seed : {1u, 2u, 3u}) {
            const cv::Mat1b truth = ellipse(angle);
            const cv::Mat1b ragged = lateralNoise(truth, seed);
            const int raw = cv::countNonZero(cleanedUp(ragged, 0.f) ^ truth);
            const int fixed = cv::countNonZero(cleanedUp(ragged, kSigma) ^ truth);
            EXPECT_GT(raw, 60) << angle << " deg, seed " << seed;
            EXPECT_LT(fixed, raw * 3 / 4) << angle << " deg, seed " << seed << ", raw " << raw;
            rawTotal += raw;
            fixedTotal += fixed;
        }
    EXPECT_LT(fixedTotal, rawTotal * 2 / 3) << "raw " << rawTotal;
}

TEST(EdgeSmoothing, HolesGapsAndThinLinesAreKept) {
    cv::Mat1b m = cv::Mat1b::zeros(120, 160);
    cv::circle(m, {40, 60}, 25, 255, cv::FILLED);
    m(cv::Rect(34, 48, 12, 24)).setTo(0);    // a hole
    m(cv::Rect(90, 20, 10, 80)).setTo(255);  // two bars one pixel apart
    m(cv::Rect(101, 20, 10, 80)).setTo(255);
    cv::line(m, {120, 10}, {150, 110}, 255, 1, cv::LINE_8);  // a one-pixel line
    const cv::Mat1b s = smoothed(m);
    EXPECT_EQ(components(s == 0, 4), components(m == 0, 4)) << "a hole was filled or a gap closed";
    EXPECT_EQ(components(s, 8), components(m, 8));
    // The hole neither grows nor shrinks: its edge, too, lies half a pixel out from the
    // foreground's boundary pixels (with the half pixel taken the other way, into the
    // foreground, it grows).
    const cv::Rect holeBox(30, 44, 20, 32);
    const int holeBefore = cv::countNonZero(m(holeBox) == 0),
              holeAfter = cv::countNonZero(s(holeBox) == 0);
    EXPECT_NEAR(holeAfter, holeBefore, 6);
    EXPECT_EQ(cv::countNonZero(s.col(100)), 0) << "the gap between the bars";
    cv::Mat1b line = cv::Mat1b::zeros(m.size());
    cv::line(line, {120, 10}, {150, 110}, 255, 1, cv::LINE_8);
    EXPECT_LE(cv::countNonZero(line & ~s), 2) << "the line's pixels";
}

TEST(EdgeSmoothing, TipsAndValleysStay) {
    // Two blades 12 px wide at the base, 6 px at their rounded tips, meeting in a V: the tips
    // and the valley are corners, which an average along the contour would round off (tips
    // shortened, the valley filled).
    cv::Mat1b m = cv::Mat1b::zeros(160, 160);
    const cv::Point base{64, 150}, left{40, 30}, right{100, 30};
    for (const cv::Point tip : {left, right}) {
        cv::fillConvexPoly(m,
                           std::vector<cv::Point>{base - cv::Point(6, 0), base + cv::Point(6, 0),
                                                  tip + cv::Point(3, 0), tip - cv::Point(3, 0)},
                           255);
        cv::circle(m, tip, 3, 255, cv::FILLED);
    }
    const cv::Mat1b changed = smoothed(m) ^ m;
    cv::Mat1b corners = cv::Mat1b::zeros(m.size());
    for (const cv::Point tip : {left, right}) cv::circle(corners, tip, 8, 255, cv::FILLED);
    int valley = 0;  // the V's lowest open pixel on its axis
    for (int y = 0; y < m.rows; ++y)
        if (m(y, 70) == 0) valley = y;
    cv::circle(corners, {70, valley}, 8, 255, cv::FILLED);
    // A few pixels may change there (many more when every point is averaged alike).
    EXPECT_LE(cv::countNonZero(changed & corners), 12);
}

TEST(EdgeSmoothing, SegmenterSmoothsByDefaultAndNotWhenOff) {
    const cv::Mat1b truth = ellipse(30.f);
    const cv::Mat1b ragged = lateralNoise(truth, 4);
    const auto wrongPixels = [&](float sigma) {
        SegmenterParams p;
        p.edgeSmoothingSigma_px = sigma;
        return cv::countNonZero(Segmenter(p).segmentMask(ragged).clusterMask ^ truth);
    };
    const int off = wrongPixels(0.f);
    EXPECT_GT(off, 100);
    EXPECT_LT(wrongPixels(SegmenterParams{}.edgeSmoothingSigma_px), off * 2 / 3) << off;
}

}  // namespace
}  // namespace meadow::capture
