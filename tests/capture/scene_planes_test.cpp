// The room's planes for plant finding (scene_planes.h): which planes a plant can stand on, how
// the tolerance grows with depth, what the removal takes and leaves, and how far above the
// floor a part stands.
#include "segmentation/scene_planes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>

#include "support/cast_scene.h"

namespace meadow::capture::segmentation::scene {
namespace {

using test::castScene;
using test::Plane;
using test::Strip;

// A level camera 0.3 m above the floor, a wall 2.5 m ahead and one 1 m to its left.
constexpr Plane kFloor{0.f, -1.f, 0.f, 0.3f};
constexpr Plane kWallAhead{0.f, 0.f, -1.f, 2.5f};
constexpr Plane kWallLeft{1.f, 0.f, 0.f, 1.f};
// A leaf seen flat, 2 cm wide, from 20 cm above the floor up to 50 cm, 1 m ahead.
constexpr Strip kLeaf{-0.01f, 0.01f, -0.2f, 0.1f, 1.f};

TEST(ScenePlanes, AFloorBearsThingsAWallBesideTheCameraAndACeilingDoNot) {
    EXPECT_TRUE(bearsThings({kFloor.nx, kFloor.ny, kFloor.nz, kFloor.d}));
    EXPECT_TRUE(bearsThings({0.f, 1.f, 0.f, -0.3f})) << "the same floor, its normal turned";
    EXPECT_FALSE(bearsThings({kWallLeft.nx, kWallLeft.ny, kWallLeft.nz, kWallLeft.d}));
    EXPECT_FALSE(bearsThings({0.f, 1.f, 0.f, 2.f})) << "a ceiling 2 m above the camera";
}

TEST(ScenePlanes, ToleranceGrowsWithTheSquareOfDepth) {
    EXPECT_FLOAT_EQ(planeTolerance_m(0.015f, 0.f), 0.015f);
    EXPECT_NEAR(planeTolerance_m(0.015f, 2.f), 0.015f + 0.04f, 1e-6f);
    EXPECT_NEAR(planeTolerance_m(0.015f, 4.f) - 0.015f,
                4.f * (planeTolerance_m(0.015f, 2.f) - 0.015f), 1e-6f);
}

TEST(ScenePlanes, RemovesTheFloorAndTheWallAndKeepsWhatStandsBeforeThem) {
    const Intrinsics k = Intrinsics::kinectV1();
    const cv::Mat1w depth = castScene(k, {kFloor, kWallAhead}, kLeaf);
    cv::Mat1b rest = depth > 0;
    const cv::Mat1b leaf = castScene(k, {}, kLeaf) > 0;
    const cv::Mat1b room = rest & ~leaf;
    StageReport report;
    const std::vector<ScenePlane> planes =
        removeScenePlanes(depth, k, SegmenterParams{}, rest, report);
    ASSERT_EQ(planes.size(), 2u) << cv::format("%zu notes", report.notes.size());
    for (const ScenePlane& p : planes) {
        // Each found plane is the floor's or the wall's, whichever way its normal points.
        const float floorLike = std::abs(p[1]), wallLike = std::abs(p[2]);
        EXPECT_TRUE(floorLike > 0.99f || wallLike > 0.99f) << p[0] << " " << p[1] << " " << p[2];
    }
    EXPECT_LE(cv::countNonZero(rest & room), 0.01 * cv::countNonZero(room))
        << "the floor and the wall are gone";
    EXPECT_GE(cv::countNonZero(rest & leaf), 0.95 * cv::countNonZero(leaf))
        << "the leaf before them stays";
}

TEST(ScenePlanes, AboveBearingIsHowHighAPartStandsOverTheFloor) {
    const Intrinsics k = Intrinsics::kinectV1();
    const cv::Mat1w depth = castScene(k, {}, kLeaf);
    const cv::Mat1b leaf = depth > 0;
    // The leaf's lowest reading lies 0.3 - 0.1 = 0.2 m above the floor (within a pixel's
    // height at 1 m, 1.7 mm).
    EXPECT_NEAR(aboveBearing_m(leaf, depth, k, {{kFloor.nx, kFloor.ny, kFloor.nz, kFloor.d}}), 0.2f,
                0.005f);
    EXPECT_EQ(
        aboveBearing_m(leaf, depth, k, {{kWallLeft.nx, kWallLeft.ny, kWallLeft.nz, kWallLeft.d}}),
        std::numeric_limits<float>::infinity())
        << "with nothing that bears things in view";
}

}  // namespace
}  // namespace meadow::capture::segmentation::scene
