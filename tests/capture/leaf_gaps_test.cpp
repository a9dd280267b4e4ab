// Leaf gaps (capture/src/segmentation/leaf_gaps.cpp): a leaf the sensor did not read along a
// short stretch comes back as one piece; pieces too far apart in space, ends that do not face
// each other and a tip that points at another leaf's side stay apart.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "meadow/capture/segmenter.h"
#include "segmentation/stages.h"

namespace meadow::capture {
namespace {

namespace seg = segmentation;

const cv::Size kFrame{640, 480};
constexpr int kLeafWidth_px = 7;

struct Piece {
    cv::Point from, to;
    std::uint16_t depth_mm = 1000;
};

struct Scene {
    cv::Mat1b mask = cv::Mat1b::zeros(kFrame);
    cv::Mat1w depth = cv::Mat1w::zeros(kFrame);
    void add(const Piece& p) {
        cv::Mat1b one = cv::Mat1b::zeros(kFrame);
        cv::line(one, p.from, p.to, 255, kLeafWidth_px);
        mask |= one;
        depth.setTo(p.depth_mm, one);
    }
};

int pieces(const cv::Mat1b& mask) {
    cv::Mat1i labels;
    return cv::connectedComponents(mask, labels, 8) - 1;
}

int bridge(Scene& s) {
    SegmenterParams params;
    params.partition = PartitionMethod::StemGraph;
    StageReport report;
    return seg::bridgeLeafGaps(s.mask, s.depth, Intrinsics::kinectV1(), params, report);
}

// A leaf rising to the right, unread over 7 px between its ends (about 1.2 cm at 1 m): one piece
// again, joined where the gap was, at the leaf's width.
TEST(LeafGaps, ALeafUnreadAlongAShortStretchIsOnePieceAgain) {
    Scene s;
    s.add({{200, 400}, {300, 300}});
    s.add({{310, 290}, {400, 200}});
    ASSERT_EQ(pieces(s.mask), 2);
    EXPECT_EQ(bridge(s), 1);
    EXPECT_EQ(pieces(s.mask), 1);
    EXPECT_TRUE(s.mask(295, 305)) << "the gap is filled along the leaf";
    EXPECT_FALSE(s.mask(290, 290)) << "and nowhere beside it";
}

// The same two pieces 10 cm apart in depth: two leaves that only line up in the image.
TEST(LeafGaps, PiecesApartInDepthStayApart) {
    Scene s;
    s.add({{200, 400}, {300, 300}});
    s.add({{310, 290}, {400, 200}, 1100});
    EXPECT_EQ(bridge(s), 0);
    EXPECT_EQ(pieces(s.mask), 2);
}

// A gap of 30 px is over 5 cm at 1 m: more than a stretch the sensor dropped.
TEST(LeafGaps, AWideGapIsNotBridged) {
    Scene s;
    s.add({{200, 400}, {300, 300}});
    s.add({{321, 279}, {400, 200}});
    EXPECT_EQ(bridge(s), 0);
}

// A leaf whose tip points at another leaf's side, and two leaves side by side whose ends do
// not face each other: nothing is joined.
TEST(LeafGaps, EndsThatDoNotFaceEachOtherStayApart) {
    Scene tipAtSide;
    tipAtSide.add({{300, 200}, {300, 400}});  // upright
    tipAtSide.add({{200, 300}, {294, 300}});  // its tip 6 px from the other's side
    EXPECT_EQ(bridge(tipAtSide), 0);

    Scene sideBySide;
    sideBySide.add({{300, 200}, {300, 300}});
    sideBySide.add({{310, 210}, {310, 310}});
    EXPECT_EQ(bridge(sideBySide), 0);
}

}  // namespace
}  // namespace meadow::capture
