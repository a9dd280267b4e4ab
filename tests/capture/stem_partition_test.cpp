// Partition by the stem (PartitionMethod::StemGraph): leaves drawn leaving a stem at three
// heights come out as three blades, each ending at its own tip, and the stem below the lowest
// leaf belongs to none.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "meadow/capture/segmenter.h"
#include "support/drawn_tuft.h"

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

// How many of the blades end within `within_px` of `tip`.
long bladesEndingNear(const Segmentation& seg, cv::Point tip, double within_px) {
    return std::count_if(seg.blades.begin(), seg.blades.end(), [&](const BladeContour& b) {
        return cv::norm(b.contour_px[static_cast<std::size_t>(b.tipIndex)] - tip) <= within_px;
    });
}

// One blade, and only one, ends within `within_px` of `tip`.
void expectOneBladeEndingAt(const Segmentation& seg, cv::Point tip, double within_px) {
    EXPECT_EQ(bladesEndingNear(seg, tip, within_px), 1) << "one blade ends at " << tip << "\n"
                                                        << seg.summary();
}

TEST(StemPartition, LeavesLeavingAStemComeOutOneABladeWithoutTheStem) {
    const Segmentation seg = segmentByStem(plantMask());
    ASSERT_EQ(seg.blades.size(), 3u) << seg.summary();
    for (const DrawnLeaf& leaf : kLeaves) expectOneBladeEndingAt(seg, leaf.tip, 6.0);
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

// What the stem took of the region: the stem below the lowest leaf, none of a leaf's far part.
TEST(StemPartition, TheStemsShareHoldsTheStemAndNoLeaf) {
    const Segmentation seg = segmentByStem(plantMask());
    ASSERT_EQ(seg.clusters.size(), 1u) << seg.summary();
    const BladeCluster& c = seg.clusters[0];
    ASSERT_FALSE(c.stemShare.empty());
    const auto inShare = [&](cv::Point p) {
        const cv::Point at = p - c.stemShareOrigin_px;
        return cv::Rect({}, c.stemShare.size()).contains(at) && c.stemShare(at) != 0;
    };
    for (const cv::Point p : {cv::Point(100, 185), cv::Point(100, 170), cv::Point(98, 160)})
        EXPECT_TRUE(inShare(p)) << p;
    for (const DrawnLeaf& leaf : kLeaves) {
        const cv::Point farPart = leaf.from + (leaf.tip - leaf.from) * 3 / 4;
        EXPECT_FALSE(inShare(farPart)) << farPart;
    }
}

// The blade that covers `through` starts (its contour's first point) nearer `base` than `tip`.
void expectBladeThroughStartsByItsBase(const Segmentation& seg, cv::Point through, cv::Point base,
                                       cv::Point tip) {
    const auto it = std::find_if(seg.blades.begin(), seg.blades.end(),
                                 [&](const BladeContour& b) { return b.covers(through); });
    ASSERT_NE(it, seg.blades.end()) << seg.summary();
    const cv::Point from = it->contour_px.front();
    EXPECT_LT(cv::norm(from - base), cv::norm(from - tip)) << "the blade starts at " << from << "\n"
                                                           << seg.summary();
}

// A leaf arching over from beside the stem (its base hidden there, so its skeleton ends free)
// comes to rest with its tip on the lowest leaf. Its base is the end by the stem, not the end
// that meets another leaf: modelled the other way round, a meadow would plant it by its tip.
TEST(StemPartition, ALeafWhoseTipRestsOnAnotherHasItsBaseByTheStem) {
    cv::Mat1b mask = plantMask();
    const cv::Point base(88, 125), arch(65, 95), tip(48, 118);
    const std::vector<cv::Point> leaf{base, arch, {52, 98}, tip};
    cv::polylines(mask, std::vector<std::vector<cv::Point>>{leaf}, false, 255, 7);
    expectBladeThroughStartsByItsBase(segmentByStem(mask), arch, base, tip);
}

// A leaf cut off from the plant (its base hidden: a region of its own) arches out and hangs its
// tip low, nearer the plant's foot than its base. It is based by the stem the plant's other
// region holds, at its end nearer the stem, not by where its own region reaches lowest.
TEST(StemPartition, ALeafInARegionOfItsOwnIsBasedByThePlantsStem) {
    cv::Mat1b mask = plantMask();
    const cv::Point base(125, 125), arch(150, 135), tip(160, 185);
    cv::polylines(mask, std::vector<std::vector<cv::Point>>{{base, arch, tip}}, false, 255, 7);
    const Segmentation seg = segmentByStem(mask);
    ASSERT_EQ(seg.clusters.size(), 2u) << seg.summary();
    expectBladeThroughStartsByItsBase(seg, arch, base, tip);
}

TEST(StemPartition, SpursOfTheEdgeAreNoLeaves) {
    cv::Mat1b mask = plantMask();
    // A bump on the stem's side, 6 px out: its skeleton branch is a spur.
    cv::circle(mask, {106, 170}, 4, 255, cv::FILLED);
    const Segmentation seg = segmentByStem(mask);
    EXPECT_EQ(seg.blades.size(), 3u) << seg.summary();
}

// A leaf that leaves the stem nearly straight on, where the stem itself bends: the leaf is the
// smoother way on, but the stem carries the two leaves above, so the stem runs on to them and
// the straight leaf is a leaf of its own.
TEST(StemPartition, TheStemRunsOnToItsLeavesWhereALeafGoesOnMoreStraightly) {
    cv::Mat1b mask = cv::Mat1b::zeros(220, 220);
    cv::line(mask, {100, 190}, {100, 150}, 255, 9);
    cv::line(mask, {100, 150}, {125, 105}, 255, 9);
    const DrawnLeaf leaves[] = {
        {{100, 150}, {90, 40}}, {{125, 105}, {160, 30}}, {{125, 105}, {195, 110}}};
    for (const DrawnLeaf& leaf : leaves) cv::line(mask, leaf.from, leaf.tip, 255, 7);
    const Segmentation seg = segmentByStem(mask);
    ASSERT_EQ(seg.clusters.size(), 1u) << seg.summary();
    const std::vector<cv::Point>& stem = seg.clusters[0].stemLine_px;
    ASSERT_GE(stem.size(), 2u) << seg.summary();
    EXPECT_LE(cv::norm(stem.front() - cv::Point(100, 190)), 6.0) << stem.front();
    EXPECT_LE(cv::norm(stem.back() - cv::Point(125, 105)), 8.0) << stem.back();
    EXPECT_EQ(seg.blades.size(), 3u) << seg.summary();
    for (const DrawnLeaf& leaf : leaves) expectOneBladeEndingAt(seg, leaf.tip, 6.0);
}

// A broad stem (a grown maize shoot's, wrapped in sheaths: 21 px) that leaves leave on
// alternate sides every 14 px, closer than the stem is wide. The junctions they make are each a
// short bridge from the next, but they are as many nodes as leaves, not one: the stem runs up
// past them, and every leaf comes out whole, on its own.
TEST(StemPartition, LeavesLeavingABroadStemCloseTogetherEachLeaveItAtTheirOwnNode) {
    cv::Mat1b mask = cv::Mat1b::zeros(240, 240);
    cv::line(mask, {120, 225}, {120, 100}, 255, 21);
    std::vector<DrawnLeaf> leaves;
    for (int i = 0; i < 5; ++i) {
        const int y = 170 - 14 * i, side = i % 2 == 0 ? -1 : 1;
        leaves.push_back({{120, y}, {120 + side * 90, y - 80}});
    }
    leaves.push_back({{120, 100}, {124, 10}});  // the top leaf, where the stem ends
    for (const DrawnLeaf& leaf : leaves) cv::line(mask, leaf.from, leaf.tip, 255, 7);
    const Segmentation seg = segmentByStem(mask);
    ASSERT_EQ(seg.clusters.size(), 1u) << seg.summary();
    const std::vector<cv::Point>& stem = seg.clusters[0].stemLine_px;
    ASSERT_GE(stem.size(), 2u) << seg.summary();
    EXPECT_LE(stem.back().y, 145) << "the stem runs up past the lowest leaves to " << stem.back();
    for (const DrawnLeaf& leaf : leaves) expectOneBladeEndingAt(seg, leaf.tip, 8.0);
}

// The top pair of leaves leaves the stem's top on both sides, each arching down: through that
// node they run on smoothly into each other, but nothing of the stem runs on there, so they are
// two leaves, not one arch across the stem's top.
TEST(StemPartition, TheTopPairOfLeavesAreTwoLeaves) {
    cv::Mat1b mask = cv::Mat1b::zeros(220, 220);
    cv::line(mask, {100, 190}, {100, 110}, 255, 9);
    cv::line(mask, {100, 160}, {165, 150}, 255, 7);  // a lower leaf
    const std::vector<cv::Point> left{{100, 110}, {70, 100}, {40, 115}};
    const std::vector<cv::Point> right{{100, 110}, {130, 100}, {160, 115}};
    cv::polylines(mask, std::vector<std::vector<cv::Point>>{left, right}, false, 255, 7);
    const Segmentation seg = segmentByStem(mask);
    EXPECT_EQ(seg.blades.size(), 3u) << seg.summary();
    for (const cv::Point tip : {cv::Point(165, 150), left.back(), right.back()})
        expectOneBladeEndingAt(seg, tip, 8.0);
    for (const BladeContour& b : seg.blades)
        EXPECT_FALSE(b.covers({70, 100}) && b.covers({130, 100})) << "no blade spans the top";
}

// A pair of leaves leaving the stem at one node on both sides, below a leaf leaving it alone:
// they too run on smoothly into each other through the node, and are two leaves.
TEST(StemPartition, APairOfLeavesLeavingOneNodeOfTheStemAreTwoLeaves) {
    cv::Mat1b mask = cv::Mat1b::zeros(220, 220);
    cv::line(mask, {100, 200}, {100, 80}, 255, 9);
    cv::line(mask, {100, 80}, {96, 15}, 255, 7);   // the top leaf, where the stem ends
    cv::line(mask, {100, 95}, {170, 60}, 255, 7);  // a leaf leaving alone
    const std::vector<cv::Point> left{{100, 140}, {70, 130}, {35, 140}};
    const std::vector<cv::Point> right{{100, 140}, {130, 130}, {165, 140}};
    cv::polylines(mask, std::vector<std::vector<cv::Point>>{left, right}, false, 255, 7);
    const Segmentation seg = segmentByStem(mask);
    EXPECT_EQ(seg.blades.size(), 4u) << seg.summary();
    for (const cv::Point tip : {cv::Point(96, 15), cv::Point(170, 60), left.back(), right.back()})
        expectOneBladeEndingAt(seg, tip, 8.0);
    for (const BladeContour& b : seg.blades)
        EXPECT_FALSE(b.covers({70, 130}) && b.covers({130, 130})) << "no blade spans the stem";
}

// The mask and depth of drawn blades, cut by the stem.
Segmentation segmentDrawnByStem(const drawn::Scene& scene) {
    SegmenterParams params;
    params.partition = PartitionMethod::StemGraph;
    return Segmenter(params).segment(drawn::draw(scene).frame);
}

drawn::Blade straightBlade(cv::Point2f base, cv::Point2f tip, float depth_m) {
    drawn::Blade b;
    b.base_px = base;
    b.tip_px = tip;
    b.control_px = 0.5f * (base + tip);
    b.baseWidth_px = 9.f;
    b.tipWidth_px = 5.f;
    b.depth_m = depth_m;
    return b;
}

const BladeContour* bladeEndingAt(const Segmentation& s, cv::Point2f tip) {
    for (const BladeContour& b : s.blades)
        if (cv::norm(cv::Point2f(b.contour_px[static_cast<std::size_t>(b.tipIndex)]) - tip) <= 8.0)
            return &b;
    return nullptr;
}

// Two leaves standing on the ground and crossing at 50 deg close the skeleton into an X: each
// comes out whole, from its own base over the crossing to its own tip, not cut in four.
TEST(StemPartition, LeavesThatCrossComeOutWholeThroughTheCrossing) {
    drawn::Scene scene;
    scene.blades = {straightBlade({280.f, 408.f}, {360.f, 248.f}, 1.00f),
                    straightBlade({360.f, 408.f}, {280.f, 248.f}, 1.03f)};
    const Segmentation s = segmentDrawnByStem(scene);
    ASSERT_EQ(s.blades.size(), 2u) << s.summary();
    const cv::Point crossing(320, 328);
    for (const drawn::Blade& leaf : scene.blades) {
        const BladeContour* b = bladeEndingAt(s, leaf.tip_px);
        ASSERT_NE(b, nullptr) << "no blade ends at " << leaf.tip_px << "\n" << s.summary();
        // Within 20 px: the skeleton starts where the plant stands, a few pixels above the base.
        EXPECT_LE(cv::norm(cv::Point2f(b->contour_px.front()) - leaf.base_px), 20.0)
            << "the blade from " << leaf.tip_px << " starts at " << b->contour_px.front();
        EXPECT_TRUE(b->covers(crossing))
            << "the blade to " << leaf.tip_px << " runs through the crossing";
    }
}

// A tuft: six blades fanning from one base, their bases a few pixels apart, so their skeletons
// meet in a tangle of junctions just above it. Each blade comes out whole, from the base to its
// own tip: the tangle is where the tuft stands, however its edges are ordered.
TEST(StemPartition, BladesFanningFromOneBaseEachComeOutFromTheBase) {
    drawn::Scene scene;
    const cv::Point2f base(320.f, 400.f);
    for (int i = 0; i < 6; ++i) {
        const float angle =
            (-50.f + 20.f * static_cast<float>(i)) * static_cast<float>(CV_PI) / 180.f;
        const cv::Point2f offset(4.f * static_cast<float>(i) - 10.f, 0.f);
        scene.blades.push_back(straightBlade(
            base + offset, base + offset + 160.f * cv::Point2f(std::sin(angle), -std::cos(angle)),
            1.f + 0.01f * static_cast<float>(i)));
    }
    const Segmentation s = segmentDrawnByStem(scene);
    EXPECT_EQ(s.blades.size(), scene.blades.size()) << s.summary();
    for (const drawn::Blade& blade : scene.blades) {
        const BladeContour* b = bladeEndingAt(s, blade.tip_px);
        ASSERT_NE(b, nullptr) << "no blade ends at " << blade.tip_px << "\n" << s.summary();
        EXPECT_LE(cv::norm(cv::Point2f(b->contour_px.front()) - blade.base_px), 25.0)
            << "the blade to " << blade.tip_px << " starts at " << b->contour_px.front();
    }
}

// A leaf (1.00 m) ends where one behind it (1.16 m) rises on in the same line, and a third
// (1.08 m) crosses both there. Direction alone joins the first two into one leaf; their depths,
// 160 mm apart at the junction, keep them apart, while the crossing leaf, level in depth, runs
// through.
TEST(StemPartition, ADepthStepAtAJunctionParts) {
    drawn::Scene scene;
    scene.blades = {straightBlade({320.f, 408.f}, {320.f, 300.f}, 1.00f),
                    straightBlade({320.f, 300.f}, {320.f, 180.f}, 1.16f),
                    straightBlade({240.f, 300.f}, {400.f, 300.f}, 1.08f)};
    const cv::Point low(320, 380), high(320, 200);
    const auto joined = [&](const Segmentation& s) {
        return std::any_of(s.blades.begin(), s.blades.end(),
                           [&](const BladeContour& b) { return b.covers(low) && b.covers(high); });
    };
    const drawn::Drawn d = drawn::draw(scene);
    SegmenterParams params;
    params.partition = PartitionMethod::StemGraph;
    params.nearDepth_m = 0.9f;  // all three leaves in the band
    params.farDepth_m = 1.3f;
    const Segmentation withDepth = Segmenter(params).segment(d.frame);
    ASSERT_FALSE(withDepth.blades.empty()) << withDepth.summary();
    EXPECT_FALSE(joined(withDepth)) << withDepth.summary();
    EXPECT_NE(bladeEndingAt(withDepth, scene.blades[1].tip_px), nullptr) << withDepth.summary();
    const Segmentation shapeOnly = Segmenter(params).segmentMask(withDepth.clusterMask);
    EXPECT_TRUE(joined(shapeOnly)) << "without depth the two are one line\n" << shapeOnly.summary();
}

}  // namespace
}  // namespace meadow::capture
