// The clusters finder (PlantFinding::Clusters) on scenes ray-cast from a few planes and one
// leaf-like strip: a plant stands on a floor, a table top or the ground; a thin strip with
// only walls beside the camera around it (a curtain's edge in a room) is not a plant.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <vector>

#include "meadow/capture/segmenter.h"
#include "support/cast_scene.h"

namespace meadow::capture {
namespace {

using test::castScene;
using test::Plane;
using test::Strip;

Segmentation findIn(const cv::Mat1w& depth, const Intrinsics& k = Intrinsics::kinectV1()) {
    SegmenterParams params;
    params.plantFinding = PlantFinding::Clusters;
    DepthFrame frame;
    frame.depth_mm = depth;
    frame.intrinsics = k;
    return Segmenter(params).segment(frame);
}

// Most (60 %) of `part`'s pixels lie in the plant's mask.
void expectInThePlant(const Segmentation& seg, const Intrinsics& k, const Strip& part) {
    const cv::Mat1b drawn = castScene(k, {}, part) > 0;
    EXPECT_GE(cv::countNonZero(seg.clusterMask & drawn), 0.6 * cv::countNonZero(drawn))
        << "the part at x " << part.x0 << ".." << part.x1 << " m is the plant's";
}

// A level camera 0.3 m above the floor, a wall 2.5 m ahead; the strip 50 cm tall at 1 m.
constexpr Plane kFloor{0.f, -1.f, 0.f, 0.3f};
constexpr Plane kWallAhead{0.f, 0.f, -1.f, 2.5f};
constexpr Strip kLeaf{-0.01f, 0.01f, -0.2f, 0.3f, 1.f};

TEST(PlantFindingScenes, AThinStripStandingOnTheFloorIsAPlant) {
    const Segmentation seg = findIn(castScene(Intrinsics::kinectV1(), {kFloor, kWallAhead}, kLeaf));
    EXPECT_FALSE(seg.noPlant) << seg.noBladesReason;
}

// The same strip between two walls beside the camera (a room's corner seen from its middle),
// no floor in view: what is thin there is the room's, and the reason says what was missing.
TEST(PlantFindingScenes, AThinStripWithOnlyWallsBesideItIsNoPlant) {
    // They meet 3 m ahead; each passes 1 m beside the camera.
    const Plane left{0.949f, 0.f, -0.316f, 0.949f}, right{-0.949f, 0.f, -0.316f, 0.949f};
    const Intrinsics k = Intrinsics::kinectV1();
    const Segmentation seg = findIn(castScene(k, {left, right}, kLeaf));
    EXPECT_TRUE(seg.noPlant);
    EXPECT_NE(seg.noBladesReason.find("no floor, table top or ground in view"), std::string::npos)
        << seg.noBladesReason;
    // The walls alone are no plant either, for the usual reason.
    EXPECT_TRUE(findIn(castScene(k, {left, right}, std::nullopt)).noPlant);
}

// A board 12 cm wide standing on the floor is no plant, and the reason says by how much the
// largest object misses a leaf's width, so a user whose plant was not found sees what to change.
// (Parts are measured where the board is left once its thick base, taken for a pot, is off.)
TEST(PlantFindingScenes, AWideBoardIsNoPlantAndTheReasonGivesItsWidth) {
    const Strip board{-0.06f, 0.06f, -0.2f, 0.3f, 1.f};
    const Segmentation seg = findIn(castScene(Intrinsics::kinectV1(), {kFloor, kWallAhead}, board));
    EXPECT_TRUE(seg.noPlant);
    const std::string said = "the largest, 0.47 m tall at 1 m, is made of parts ";
    const auto at = seg.noBladesReason.find(said);
    ASSERT_NE(at, std::string::npos) << seg.noBladesReason;
    EXPECT_GT(std::stof(seg.noBladesReason.substr(at + said.size())), 4.f) << seg.noBladesReason;
    EXPECT_NE(seg.noBladesReason.find("(leaves: under 4 cm, or 6 cm when 20 times as long)"),
              std::string::npos)
        << seg.noBladesReason;
}

// Beside the plant, a board too wide to be one: the plant is found, and the board is among the
// objects left out, outlined where it stands, with why; alone, it is left out the same way.
TEST(PlantFindingScenes, ObjectsLeftOutAreOutlinedWithWhy) {
    const Intrinsics k = Intrinsics::kinectV1();
    const Strip board{0.15f, 0.27f, -0.2f, 0.3f, 1.2f};
    const cv::Point boardCentre(static_cast<int>(k.cx_px + k.fx_px * 0.21f / 1.2f),
                                static_cast<int>(k.cy_px + k.fy_px * 0.f / 1.2f));
    const auto boardLeftOut = [&](const Segmentation& seg) {
        return std::any_of(seg.leftOut.begin(), seg.leftOut.end(), [&](const LeftOutObject& o) {
            return o.why == "too wide" &&
                   cv::pointPolygonTest(o.outline_px, cv::Point2f(boardCentre), false) > 0;
        });
    };
    const Segmentation both =
        findIn(castScene(k, {kFloor, kWallAhead}, std::vector<Strip>{kLeaf, board}));
    ASSERT_FALSE(both.noPlant) << both.noBladesReason;
    EXPECT_TRUE(boardLeftOut(both));
    const Segmentation alone = findIn(castScene(k, {kFloor, kWallAhead}, board));
    EXPECT_TRUE(alone.noPlant);
    EXPECT_TRUE(boardLeftOut(alone));
}

// A young plant seen from too far covers less of the view than a plant must (but over half of
// it; the floor's removal takes its lowest 3 cm), beside a board that is larger but too wide:
// the reason names the board as the largest object, the small thin one as what may be the
// plant, and what to do.
TEST(PlantFindingScenes, AThinObjectOnlyTooSmallIsNamedWithWhatToDo) {
    const Strip board{0.15f, 0.27f, -0.2f, 0.3f, 1.2f};
    const Strip young{-0.01f, 0.01f, 0.03f, 0.3f, 1.f};
    const Segmentation seg = findIn(
        castScene(Intrinsics::kinectV1(), {kFloor, kWallAhead}, std::vector<Strip>{board, young}));
    EXPECT_TRUE(seg.noPlant);
    EXPECT_NE(seg.noBladesReason.find("the largest, "), std::string::npos) << seg.noBladesReason;
    EXPECT_NE(seg.noBladesReason.find("the largest thin one, 0.24 m tall at 1 m, is too small"),
              std::string::npos)
        << seg.noBladesReason;
    EXPECT_NE(seg.noBladesReason.find("bring the camera closer"), std::string::npos);
}

// The same young plant alone: the largest object is itself only too small, and the reason says
// what to do right after it.
TEST(PlantFindingScenes, APlantOnlyTooSmallAloneIsToldToComeCloser) {
    const Strip young{-0.01f, 0.01f, 0.03f, 0.3f, 1.f};
    const Segmentation seg = findIn(castScene(Intrinsics::kinectV1(), {kFloor, kWallAhead}, young));
    EXPECT_TRUE(seg.noPlant);
    const std::string said = "the largest, 0.24 m tall at 1 m, is too small (";
    const auto at = seg.noBladesReason.find(said);
    ASSERT_NE(at, std::string::npos) << seg.noBladesReason;
    const auto closer =
        seg.noBladesReason.find("): bring the camera closer if it is the plant", at);
    EXPECT_NE(closer, std::string::npos) << seg.noBladesReason;
    EXPECT_EQ(seg.noBladesReason.find("the largest thin one"), std::string::npos)
        << "said once: " << seg.noBladesReason;
}

// A young plant as small standing in a pot as tall as wide: a seedling seen edge-on covers few
// pixels, but what is thin and grows out of a pot of its own is the plant, down to half a
// plant's pixels (about 1400 of 2457 here).
TEST(PlantFindingScenes, AYoungPlantTooSmallAloneIsThePlantInItsPot) {
    const Strip young{-0.0125f, 0.0125f, 0.03f, 0.2f, 1.f}, pot{-0.05f, 0.05f, 0.2f, 0.3f, 1.f};
    const Segmentation seg = findIn(
        castScene(Intrinsics::kinectV1(), {kFloor, kWallAhead}, std::vector<Strip>{young, pot}));
    ASSERT_FALSE(seg.noPlant) << seg.noBladesReason;
    expectInThePlant(seg, Intrinsics::kinectV1(), young);
    // A seventh of a plant's pixels is too small, pot or not.
    const Strip stub{-0.005f, 0.005f, 0.1f, 0.2f, 1.f};
    const Segmentation stubSeg = findIn(
        castScene(Intrinsics::kinectV1(), {kFloor, kWallAhead}, std::vector<Strip>{stub, pot}));
    EXPECT_TRUE(stubSeg.noPlant);
}

// Beyond the distances the guide tests, a broad-leaved plant's leaves blur into one another
// (docs/capture.md): parts wider than a grass's and too short for a broad-leaved plant's. Seen
// so far off, the reason says to come closer if it is one; the same board within the guide's
// distances is only too wide, as a board is.
TEST(PlantFindingScenes, ABroadPartFarOffIsToldToComeCloserIfItIsABroadLeavedPlant) {
    const std::string closer = "bring the camera closer if it is a broad-leaved plant";
    const Strip far{-0.05f, 0.05f, -0.5f, 0.3f, 1.6f};
    const Segmentation seen = findIn(castScene(Intrinsics::kinectV1(), {kFloor, kWallAhead}, far));
    EXPECT_TRUE(seen.noPlant);
    EXPECT_NE(seen.noBladesReason.find("times as long (leaves: under 4 cm, or 6 cm when 20 times "
                                       "as long): " +
                                       closer),
              std::string::npos)
        << seen.noBladesReason;
    const Strip near{-0.05f, 0.05f, -0.4f, 0.3f, 1.1f};
    const Segmentation nearer =
        findIn(castScene(Intrinsics::kinectV1(), {kFloor, kWallAhead}, near));
    EXPECT_TRUE(nearer.noPlant);
    EXPECT_NE(nearer.noBladesReason.find("times as long (leaves: "), std::string::npos)
        << nearer.noBladesReason;
    EXPECT_EQ(nearer.noBladesReason.find(closer), std::string::npos) << nearer.noBladesReason;
}

// A wide-angle camera (a RealSense D435's 848 x 480 at 430 px focal length, 89 degrees across)
// sees a strip 60 cm tall at the same distance on fewer pixels, and a smaller share of its image
// (0.5 % against 1.2 %, under the 0.8 % a plant covers): the angle it covers keeps it, so both
// find it. A strip 20 cm tall covers too little for either.
TEST(PlantFindingScenes, AWideAngleCameraFindsThePlantANarrowOneFindsAtTheSameDistance) {
    Intrinsics wide;
    wide.width_px = 848;
    wide.fx_px = wide.fy_px = 430.f;
    wide.cx_px = 423.5f;
    const Strip tallLeaf{kLeaf.x0, kLeaf.x1, -0.3f, kLeaf.y1, kLeaf.z};
    for (const Intrinsics& k : {Intrinsics::kinectV1(), wide}) {
        const Segmentation seg = findIn(castScene(k, {kFloor, kWallAhead}, tallLeaf), k);
        EXPECT_FALSE(seg.noPlant) << k.width_px << " px wide: " << seg.noBladesReason;
        const Strip shortLeaf{kLeaf.x0, kLeaf.x1, 0.1f, kLeaf.y1, kLeaf.z};
        const Segmentation small = findIn(castScene(k, {kFloor, kWallAhead}, shortLeaf), k);
        EXPECT_TRUE(small.noPlant) << k.width_px << " px wide";
        EXPECT_NE(small.noBladesReason.find("none large enough"), std::string::npos)
            << small.noBladesReason;
    }
}

// Readings scattered as a stereo camera's are, uniformly within +-a z^2 (a in mm per square
// metre): neighbours a metre or two away differ by tens of millimetres.
cv::Mat1w withStereoScatter(cv::Mat1w depth, float a_mm_per_m2) {
    cv::RNG rng(7);
    for (auto& d : depth) {
        if (d == 0) continue;
        const float z_m = static_cast<float>(d) / 1000.f;
        d = static_cast<std::uint16_t>(static_cast<float>(d) +
                                       rng.uniform(-a_mm_per_m2, a_mm_per_m2) * z_m * z_m);
    }
    return depth;
}

// A strip 4 cm wide and 1 m tall, 2 m away, read by a camera that scatters its readings by up
// to 24 mm there (a RealSense D435 at that distance): neighbouring readings on the strip differ by
// more than the 20 mm a depth jump takes near the camera, so a fixed jump would cut it into
// pieces too small to be a plant. The jumps follow the frame's own steps between neighbours.
TEST(PlantFindingScenes, AFarPlantReadByAStereoCameraStaysWhole) {
    const Strip tallLeaf{-0.02f, 0.02f, -0.7f, 0.3f, 2.f};
    const cv::Mat1w exact = castScene(Intrinsics::kinectV1(), {kFloor, kWallAhead}, tallLeaf);
    const Segmentation seg = findIn(withStereoScatter(exact, 6.f));
    EXPECT_FALSE(seg.noPlant) << seg.noBladesReason;
    // The plant's mask holds most of the strip's pixels.
    const cv::Mat1b strip = castScene(Intrinsics::kinectV1(), {}, tallLeaf) > 0;
    ASSERT_FALSE(seg.clusterMask.empty());
    EXPECT_GE(cv::countNonZero(seg.clusterMask & strip), 0.8 * cv::countNonZero(strip));
}

// A plant the sensor broke into two pieces: a pot on the floor with the stem, and beside it,
// 2.5 cm off to the side and 2.5 cm behind, a broad leaf's base 6 cm across with the leaf
// going on above it, half a metre above the floor. The piece's thick base is no pot: the piece
// joins the plant, its base too, and the plant stands on the pot that stands on the floor.
TEST(PlantFindingScenes, APieceOfThePlantWithABroadBaseHighAboveTheFloorJoinsIt) {
    const Intrinsics k = Intrinsics::kinectV1();
    const Strip pot{-0.06f, 0.06f, 0.18f, 0.3f, 1.f}, stem{-0.01f, 0.01f, -0.35f, 0.18f, 1.f};
    const Strip leafBase{0.035f, 0.095f, -0.3f, -0.24f, 1.025f};
    const Strip leaf{0.055f, 0.075f, -0.42f, -0.3f, 1.025f};
    const Segmentation seg =
        findIn(castScene(k, {kFloor, kWallAhead}, std::vector<Strip>{pot, stem, leafBase, leaf}));
    ASSERT_FALSE(seg.noPlant) << seg.noBladesReason;
    ASSERT_FALSE(seg.clusterMask.empty());
    for (const Strip& part : {leafBase, leaf}) expectInThePlant(seg, k, part);
    // Where the plant stands: the top of the pot, row 240 + 0.18 m x 525 px / 1 m.
    ASSERT_TRUE(seg.plantBase_px.has_value());
    EXPECT_NEAR(seg.plantBase_px->y, 240.f + 0.18f * k.fy_px, 6.f);
}

// The plant's pot is taken off the plant and outlined among what was left out, so that a user
// sees in the overlay where the pot's cut ends; the stem above it is the plant's.
TEST(PlantFindingScenes, ThePlantsPotIsOutlinedAsThePot) {
    const Intrinsics k = Intrinsics::kinectV1();
    const Strip pot{-0.06f, 0.06f, 0.18f, 0.3f, 1.f}, stem{-0.01f, 0.01f, -0.35f, 0.18f, 1.f};
    const Segmentation seg =
        findIn(castScene(k, {kFloor, kWallAhead}, std::vector<Strip>{pot, stem, kLeaf}));
    ASSERT_FALSE(seg.noPlant) << seg.noBladesReason;
    const auto at = [&](float y_m) {
        return cv::Point2f(k.cx_px, k.cy_px + k.fy_px * y_m);  // on the axis, 1 m away
    };
    const auto potOutline = std::find_if(seg.leftOut.begin(), seg.leftOut.end(),
                                         [](const LeftOutObject& o) { return o.why == "pot"; });
    ASSERT_NE(potOutline, seg.leftOut.end());
    EXPECT_GT(cv::pointPolygonTest(potOutline->outline_px, at(0.24f), false), 0) << "its middle";
    EXPECT_LT(cv::pointPolygonTest(potOutline->outline_px, at(0.1f), false), 0) << "the stem";
    EXPECT_GT(seg.clusterMask(at(0.1f)), 0) << "the stem is the plant's";
}

// A broad leaf hanging before the stem, 2.5 cm nearer and 2.5 cm to the side, is the piece
// nearest the view's centre; the rest of the plant (pot, stem, a leaf reaching left) lies off
// to the left. The rest is larger and stands in the pot: it is the plant the piece belongs to,
// and it joins, pot and all.
TEST(PlantFindingScenes, ThePlantInItsPotJoinsTheLeafPieceTheCameraIsAimedAt) {
    const Intrinsics k = Intrinsics::kinectV1();
    const Strip pot{-0.09f, 0.03f, 0.18f, 0.3f, 1.f}, stem{-0.04f, -0.02f, -0.35f, 0.18f, 1.f};
    const Strip arm{-0.3f, -0.02f, -0.36f, -0.34f, 1.f}, hanging{-0.3f, -0.28f, -0.36f, 0.f, 1.f};
    const Strip piece{0.005f, 0.035f, -0.25f, 0.1f, 0.975f};
    const Segmentation seg = findIn(
        castScene(k, {kFloor, kWallAhead}, std::vector<Strip>{pot, stem, arm, hanging, piece}));
    ASSERT_FALSE(seg.noPlant) << seg.noBladesReason;
    ASSERT_FALSE(seg.clusterMask.empty());
    for (const Strip& part : {piece, stem, hanging}) expectInThePlant(seg, k, part);
    ASSERT_TRUE(seg.plantBase_px.has_value());
    EXPECT_NEAR(seg.plantBase_px->y, 240.f + 0.18f * k.fy_px, 6.f) << "it stands on its pot";
}

// A plant 2.2 m away that the sensor broke into two pieces: the pot with a stem 4 cm wide and a
// leaf reaching left, and beside the stem, 4 cm off to the side and 6 cm behind, a leaf on its
// own (its base hidden behind the stem). At that depth readings scatter over centimetres and
// pieces of one plant part by more than they do near the camera: the leaf joins.
TEST(PlantFindingScenes, AFarPlantsLeafSixCentimetresBehindItsStemJoinsIt) {
    const Intrinsics k = Intrinsics::kinectV1();
    constexpr float z = 2.2f;
    const Strip pot{-0.06f, 0.06f, 0.18f, 0.3f, z}, stem{-0.02f, 0.02f, -0.7f, 0.18f, z};
    const Strip arm{-0.4f, -0.02f, -0.5f, -0.47f, z};
    const Strip behind{0.06f, 0.08f, -0.6f, -0.2f, z + 0.06f};
    const Segmentation seg =
        findIn(castScene(k, {kFloor, kWallAhead}, std::vector<Strip>{pot, stem, arm, behind}));
    ASSERT_FALSE(seg.noPlant) << seg.noBladesReason;
    ASSERT_FALSE(seg.clusterMask.empty());
    for (const Strip& part : {stem, behind}) expectInThePlant(seg, k, part);
}

// Grass seen from straight above stands on the ground, which faces the camera.
TEST(PlantFindingScenes, AThinStripBeforeTheGroundSeenFromAboveIsAPlant) {
    const Plane groundBelow{0.f, 0.f, -1.f, 1.2f};
    const Segmentation seg = findIn(castScene(Intrinsics::kinectV1(), {groundBelow}, kLeaf));
    EXPECT_FALSE(seg.noPlant) << seg.noBladesReason;
}

}  // namespace
}  // namespace meadow::capture
