// Hausdorff metrics on cases small enough to compute by hand.
#include "meadow/modeling/hausdorff.h"

#include <gtest/gtest.h>

#include <cmath>

namespace meadow::modeling {
namespace {

// Five knots on the x axis, 1 m apart; the middle one lifted by 0.5 m in y.
const std::vector<glm::vec3> kKnots{{0, 0, 0}, {1, 0, 0}, {2, 0.5f, 0}, {3, 0, 0}, {4, 0, 0}};

TEST(Hausdorff, RefinedHausdorffIsLargestDistanceFromCulledToNearestKeptKnot) {
    // Kept 0, 2, 4: culled 1 is sqrt(1 + 0.25) from knot 2 and 1 from knot 0 -> 1; culled 3 -> 1.
    EXPECT_FLOAT_EQ(refinedHausdorff_m(kKnots, {0, 2, 4}), 1.f);
    // Kept 0, 4: culled 2 is sqrt(4 + 0.25) from both ends; culled 1 and 3 are 1 away.
    EXPECT_FLOAT_EQ(refinedHausdorff_m(kKnots, {0, 4}), std::sqrt(4.25f));
    EXPECT_FLOAT_EQ(refinedHausdorff_m(kKnots, {0, 1, 2, 3, 4}), 0.f);
    EXPECT_THROW(refinedHausdorff_m(kKnots, {0, 4, 2}), std::invalid_argument);
    EXPECT_THROW(refinedHausdorff_m(kKnots, {0, 5}), std::invalid_argument);
}

TEST(Hausdorff, PointSegmentDistanceClampsToEnds) {
    EXPECT_FLOAT_EQ(pointSegmentDistance_m({0.5f, 2, 0}, {0, 0, 0}, {1, 0, 0}), 2.f);
    EXPECT_FLOAT_EQ(pointSegmentDistance_m({-3, 4, 0}, {0, 0, 0}, {1, 0, 0}), 5.f);
    EXPECT_FLOAT_EQ(pointSegmentDistance_m({1, 1, 0}, {0, 0, 0}, {0, 0, 0}), std::sqrt(2.f));
}

TEST(Hausdorff, PolylineHausdorffOfTentAgainstItsBase) {
    // Full polyline is the tent; refined drops the apex: the deviation is the apex height 0.5,
    // in both directions (the base's point under the apex is 0.5 from the tent too).
    const std::vector<glm::vec3> base{{0, 0, 0}, {4, 0, 0}};
    EXPECT_NEAR(directedHausdorff_m(kKnots, base), 0.5f, 1e-6f);
    EXPECT_NEAR(directedHausdorff_m(base, kKnots), 0.5f * std::cos(std::atan(0.5f)),
                0.02f);  // sampled
    EXPECT_NEAR(hausdorff_m(kKnots, base), 0.5f, 1e-6f);
    EXPECT_FLOAT_EQ(hausdorff_m(kKnots, kKnots), 0.f);
}

TEST(Hausdorff, DirectedDistanceFindsPeakInsideASegment) {
    // A segment passing over a V: the largest distance is at the segment's middle, not at a vertex.
    const std::vector<glm::vec3> segment{{-1, 1, 0}, {1, 1, 0}};
    const std::vector<glm::vec3> v{{-1, 1, 0}, {0, 0, 0}, {1, 1, 0}};
    EXPECT_NEAR(directedHausdorff_m(segment, v, 8), std::sqrt(0.5f), 1e-6f);
}

TEST(Hausdorff, EvaluateRefinementTakesMeanAndWorstOverFrames) {
    // Frame 0: the tent; frame 1: flat (nothing deviates).
    std::vector<glm::vec3> flat = kKnots;
    flat[2].y = 0.f;
    const KnotTrajectories frames{kKnots, flat};
    const RefinementError e = evaluateRefinement(frames, {0, 4});
    // Refined Hausdorff: frame 0 sqrt(4.25), frame 1 2.
    EXPECT_NEAR(e.refinedHausdorffMean_m, 0.5f * (std::sqrt(4.25f) + 2.f), 1e-6f);
    EXPECT_NEAR(e.refinedHausdorffMax_m, std::sqrt(4.25f), 1e-6f);
    EXPECT_NEAR(e.maxDeviation_m, 0.5f, 1e-6f);
    EXPECT_NEAR(e.hausdorffMax_m, 0.5f, 1e-6f);
}

}  // namespace
}  // namespace meadow::modeling
