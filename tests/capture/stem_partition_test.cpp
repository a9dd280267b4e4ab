// Partition by the stem (PartitionMethod::StemGraph): leaves drawn leaving a stem at three
// heights come out as three blades, each ending at its own tip, and the stem below the lowest
// leaf belongs to none.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "meadow/capture/segmenter.h"

namespace meadow::capture {
namespace {

struct DrawnLeaf {
    cv::Point from, tip;
};

// A stem from (100, 190) up to (100, 110), leaves leaving it at 150 and 110, and the stem going
// on into the top leaf.
const DrawnLeaf kLeaves[] = {
    {{100, 150}, {30, 110}}, {{100, 110}, {170, 80}}, {{100, 110}, {92, 15}}};

cv::Mat1b plantMask() {
    cv::Mat1b mask = cv::Mat1b::zeros(220, 220);
    cv::line(mask, {100, 190}, {100, 110}, 255, 9);
    for (const DrawnLeaf& leaf : kLeaves) cv::line(mask, leaf.from, leaf.tip, 255, 7);
    return mask;
}

// The mask cut by the stem, its edges as drawn (no smoothing).
Segmentation segmentByStem(const cv::Mat1b& mask) {
    SegmenterParams params;
    params.partition = PartitionMethod::StemGraph;
    params.edgeSmoothingSigma_px = 0.f;
    return Segmenter(params).segmentMask(mask);
}

TEST(StemPartition, LeavesLeavingAStemComeOutOneABladeWithoutTheStem) {
    const Segmentation seg = segmentByStem(plantMask());
    ASSERT_EQ(seg.blades.size(), 3u) << seg.summary();
    for (const DrawnLeaf& leaf : kLeaves) {
        int found = 0;
        for (const BladeContour& b : seg.blades) {
            const cv::Point tip = b.contour_px[static_cast<std::size_t>(b.tipIndex)];
            found += cv::norm(tip - leaf.tip) <= 6.0;
        }
        EXPECT_EQ(found, 1) << "one blade ends at the tip " << leaf.tip;
    }
    for (const BladeContour& b : seg.blades) {
        EXPECT_FALSE(b.covers({100, 175})) << "the stem below the lowest leaf is no leaf's";
        EXPECT_FALSE(b.covers({100, 185}));
    }
}

// The stem's line runs from where the plant stands, the stem's foot at row 190, to where the
// highest leaves leave it at (100, 110).
TEST(StemPartition, TheStemRunsFromItsFootToTheHighestNode) {
    const Segmentation seg = segmentByStem(plantMask());
    ASSERT_EQ(seg.clusters.size(), 1u) << seg.summary();
    const std::vector<cv::Point>& stem = seg.clusters[0].stemLine_px;
    ASSERT_GE(stem.size(), 2u);
    EXPECT_LE(cv::norm(stem.front() - cv::Point(100, 190)), 6.0) << stem.front();
    EXPECT_LE(cv::norm(stem.back() - cv::Point(100, 110)), 6.0) << stem.back();
}

TEST(StemPartition, SpursOfTheEdgeAreNoLeaves) {
    cv::Mat1b mask = plantMask();
    // A bump on the stem's side, 6 px out: its skeleton branch is a spur.
    cv::circle(mask, {106, 170}, 4, 255, cv::FILLED);
    const Segmentation seg = segmentByStem(mask);
    EXPECT_EQ(seg.blades.size(), 3u) << seg.summary();
}

}  // namespace
}  // namespace meadow::capture
