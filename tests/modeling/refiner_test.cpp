// Skeleton refining by movement similarity (Fan & Sheng 2017, Eq. 1-3, Algorithm 1), its
// baselines, the chain simulation behind it, and the Fig. 12 comparison.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "meadow/modeling/chain_simulation.h"
#include "meadow/modeling/hausdorff.h"
#include "meadow/modeling/quadratic_bezier.h"
#include "meadow/modeling/skeleton.h"
#include "meadow/modeling/skeleton_refiner.h"

namespace meadow::modeling {
namespace {

constexpr int kFullKnots = 128;  // Fan & Sheng's Fig. 12 starts from 128 knots

// A rest skeleton in the blade-local frame: a quadratic Bezier resampled to n knots.
std::vector<glm::vec3> restSkeleton(float height_m, float bend, int n = kFullKnots) {
    const QuadraticBezier b{{0.f, 0.f, 0.f},
                            {0.05f * bend * height_m, 0.55f * height_m, 0.f},
                            {bend * height_m, (1.f - 0.5f * bend * bend) * height_m, 0.f}};
    std::vector<glm::vec3> dense;
    for (int i = 0; i <= 1000; ++i) dense.push_back(b.at(i / 1000.f));
    return resampleByArcLength(dense, n);
}

void expectValidRefinement(const std::vector<int>& kept, int n, int m, const char* who) {
    ASSERT_EQ(static_cast<int>(kept.size()), m) << who;
    EXPECT_EQ(kept.front(), 0) << who;
    EXPECT_EQ(kept.back(), n - 1) << who;
    for (std::size_t i = 1; i < kept.size(); ++i) EXPECT_LT(kept[i - 1], kept[i]) << who;
}

TEST(Refiner, MeanDistanceIsAverageOverFrames) {
    const KnotTrajectories frames{{{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {3, 0, 0}}};
    EXPECT_FLOAT_EQ(meanDistance_m(frames, 0, 1), 2.f);
}

TEST(Refiner, MovementVarianceIsZeroForRigidTranslationAndAPopulationVariance) {
    // Both knots translate together: the relative vector is constant.
    const KnotTrajectories rigid{
        {{0, 0, 0}, {1, 0, 0}}, {{5, 2, 1}, {6, 2, 1}}, {{-1, 3, 0}, {0, 3, 0}}};
    EXPECT_NEAR(movementVariance_m2(rigid, 0, 1), 0.f, 1e-10f);
    // Relative vector alternates (1, +d, 0) and (1, -d, 0): mean (1, 0, 0), variance d^2
    // (population, 1/n, not 1/(n-1)).
    const float d = 0.3f;
    const KnotTrajectories swing{{{0, 0, 0}, {1, d, 0}},
                                 {{0, 0, 0}, {1, -d, 0}},
                                 {{0, 0, 0}, {1, d, 0}},
                                 {{0, 0, 0}, {1, -d, 0}}};
    EXPECT_NEAR(movementVariance_m2(swing, 0, 1), d * d, 1e-7f);
    // Three frames with relative x = 0, 1, 5: variance of {0, 1, 5} = 14 / 3.
    const KnotTrajectories three{
        {{0, 0, 0}, {0, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {5, 0, 0}}};
    EXPECT_NEAR(movementVariance_m2(three, 0, 1), 14.f / 3.f, 1e-5f);
}

TEST(Refiner, MovementDifferenceMixesNormalisedTerms) {
    EXPECT_FLOAT_EQ(movementDifference(2.f, 8.f, 0.25f, 1.f, 1.f), 0.25f * 2.f + 0.75f * 8.f);
    EXPECT_FLOAT_EQ(movementDifference(2.f, 8.f, 0.5f, 2.f, 4.f), 0.5f * 1.f + 0.5f * 2.f);
}

TEST(Refiner, AlgorithmOneKeepsEndpointsAndReturnsMKnots) {
    const auto rest = restSkeleton(0.15f, 0.4f);
    const KnotTrajectories frames = simulateChain(rest);
    for (int m : {2, 3, 8, 16, 64, 127, 128}) {
        expectValidRefinement(refineByMovementSimilarity(frames, m), kFullKnots, m,
                              "movement similarity");
        expectValidRefinement(refineGeometryOnly(rest, m), kFullKnots, m, "geometry only");
        expectValidRefinement(refineMean(rest, m), kFullKnots, m, "mean");
        expectValidRefinement(refineRandom(kFullKnots, m, 7), kFullKnots, m, "random");
    }
    EXPECT_THROW(refineByMovementSimilarity(frames, 1), std::invalid_argument);
    RefinerParams bad;
    bad.mu = 1.5f;
    EXPECT_THROW(refineByMovementSimilarity(frames, 8, bad), std::invalid_argument);
}

// Algorithm 1's steps do not depend on m: one run down to the ends gives every count's knots.
TEST(Refiner, OneDropOrderGivesAlgorithmOnesKnotsForEveryCount) {
    const auto rest = restSkeleton(0.15f, 0.4f);
    const KnotTrajectories frames = simulateChain(rest);
    const std::vector<int> order = movementSimilarityDropOrder(frames);
    ASSERT_EQ(order.size(), static_cast<std::size_t>(kFullKnots - 2));
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "a knot twice";
    EXPECT_GT(sorted.front(), 0) << "the base is never dropped";
    EXPECT_LT(sorted.back(), kFullKnots - 1) << "the tip is never dropped";
    for (int m : {2, 3, 8, 16, 64, 127, 128})
        EXPECT_EQ(keptAfterDrops(kFullKnots, order, m), refineByMovementSimilarity(frames, m))
            << m << " knots";
    EXPECT_THROW(keptAfterDrops(kFullKnots, order, 1), std::invalid_argument);
}

TEST(Refiner, MeanRefinerSpacesKnotsEvenly) {
    const auto rest = restSkeleton(0.1f, 0.f, 13);  // straight, 12 equal edges
    EXPECT_EQ(refineMean(rest, 5), (std::vector<int>{0, 3, 6, 9, 12}));
}

TEST(Refiner, GeometryOnlyMergesShortestEdgeFirst) {
    // Edges: 1, 0.1, 1, 1. The 0.1 edge (knots 1-2) merges first.
    const std::vector<glm::vec3> knots{
        {0, 0, 0}, {1, 0, 0}, {1.1f, 0, 0}, {2.1f, 0, 0}, {3.1f, 0, 0}};
    const auto kept = refineGeometryOnly(knots, 4);
    EXPECT_TRUE(kept == (std::vector<int>{0, 1, 3, 4}) || kept == (std::vector<int>{0, 2, 3, 4}));
}

TEST(Refiner, MovementSimilarityMergesKnotsThatMoveTogether) {
    // Knots 1 and 2 move rigidly together (pure translation); 3 moves independently. With
    // mu = 0 only the variance counts, so the rigid pair merges first.
    KnotTrajectories frames;
    for (int t = 0; t < 10; ++t) {
        const float s = std::sin(0.7f * t);
        frames.push_back({{0, 0, 0}, {1 + s, 1, 0}, {1 + s, 2, 0}, {0.5f * s, 3, s}, {0, 4, 0}});
    }
    RefinerParams p;
    p.mu = 0.f;
    const auto kept = refineByMovementSimilarity(frames, 4, p);
    EXPECT_TRUE(kept == (std::vector<int>{0, 1, 3, 4}) || kept == (std::vector<int>{0, 2, 3, 4}))
        << kept[0] << kept[1] << kept[2] << kept[3];
}

TEST(ChainSimulation, IsDeterministicClampsRootAndKeepsSegmentLengths) {
    const auto rest = restSkeleton(0.15f, 0.3f, 32);
    const KnotTrajectories a = simulateChain(rest), b = simulateChain(rest);
    ASSERT_EQ(a.size(), 60u);
    EXPECT_EQ(a.back(), b.back());
    float tipTravel = 0.f, midTravel = 0.f;
    for (const auto& f : a) {
        EXPECT_EQ(f[0], rest[0]);
        EXPECT_EQ(f[1], rest[1]);
        for (std::size_t i = 1; i < f.size(); ++i) {
            const float restLen = glm::distance(rest[i - 1], rest[i]);
            // PBD with a finite number of sweeps leaves some stretch under the strongest gusts.
            EXPECT_NEAR(glm::distance(f[i - 1], f[i]), restLen, 0.15f * restLen) << "segment " << i;
        }
        tipTravel = std::max(tipTravel, glm::distance(f.back(), rest.back()));
        midTravel = std::max(midTravel, glm::distance(f[16], rest[16]));
    }
    // The wind moves the blade visibly, and the tip more than the middle (cantilever).
    EXPECT_GT(tipTravel, 0.05f * 0.15f);
    EXPECT_LT(tipTravel, 0.6f * 0.15f);
    EXPECT_GT(tipTravel, midTravel);
    ChainSimulationParams other;
    other.seed = 2;
    EXPECT_NE(simulateChain(rest, other).back(), a.back());
}

}  // namespace
}  // namespace meadow::modeling
