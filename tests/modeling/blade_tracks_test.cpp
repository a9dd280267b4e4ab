// Observations of one blade across fused groups are linked into one track (blade_tracks.h).
#include "meadow/modeling/blade_tracks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

namespace meadow::modeling {
namespace {

constexpr int kPoints = 128;

// A straight blade of `length_m` from a root 0.7 m in front of the camera, leaning `lean_rad`
// sideways from +Y (image up is -Y in camera space; the sign does not matter here), its points
// shifted by `offset_m`.
Skeleton straightBlade(float lean_rad, float length_m = 0.15f, glm::vec3 offset_m = {},
                       float width_m = 0.01f) {
    Skeleton s;
    const glm::vec3 root(0.f, 0.05f, 0.7f);
    const glm::vec3 dir(std::sin(lean_rad), -std::cos(lean_rad), 0.f);
    for (int j = 0; j < kPoints; ++j) {
        const float f = static_cast<float>(j) / (kPoints - 1);
        s.points_m.push_back(root + f * length_m * dir + offset_m);
        s.width_m.push_back(width_m * (1.f - 0.5f * f));
        s.arcFraction.push_back(f);
        s.depth_m.push_back(s.points_m.back().z);
        s.midline_px.push_back({320.f + 400.f * f * dir.x, 300.f - 400.f * f});
        s.across_px.push_back({1.f, 0.f});
        s.width_px.push_back(8.f * (1.f - 0.5f * f));
    }
    return s;
}

TEST(BladeTracks, EachBladeSeenInEveryGroupBecomesOneTrack) {
    // Two blades 0.3 rad apart (tips 45 mm apart), each seen in three groups with a 1.5 mm jitter.
    std::vector<BladeObservation> obs;
    for (int g = 0; g < 3; ++g) {
        const glm::vec3 jitter(0.0015f * (g - 1), 0.f, 0.001f * g);
        obs.push_back({g, straightBlade(-0.15f, 0.15f, jitter)});
        obs.push_back({g, straightBlade(0.15f, 0.15f, -jitter)});
    }
    const auto tracks = trackBlades(obs);
    ASSERT_EQ(tracks.size(), 2u);
    EXPECT_EQ(tracks[0], (std::vector<std::size_t>{0, 2, 4}));
    EXPECT_EQ(tracks[1], (std::vector<std::size_t>{1, 3, 5}));
}

TEST(BladeTracks, ABladeThatMovedFartherThanTheToleranceStartsItsOwnTrack) {
    // The tip swung 40 mm (a gust): the upper three quarters lie 25 mm from where they were on
    // average, 0.17 of the length (the tolerance is 0.08); a swing of 0.75 mm stays in the track.
    const std::vector<BladeObservation> obs{
        {0, straightBlade(0.f)}, {1, straightBlade(0.27f)}, {2, straightBlade(0.005f)}};
    const auto tracks = trackBlades(obs);
    ASSERT_EQ(tracks.size(), 2u);
    EXPECT_EQ(tracks[0], (std::vector<std::size_t>{0, 2}));
    EXPECT_EQ(tracks[1], (std::vector<std::size_t>{1}));
}

TEST(BladeTracks, ATrackTakesOneObservationPerGroupTheNearest) {
    // Group 1 holds two pieces near the blade of group 0 (a blade cut in two would be one case):
    // the nearer joins, the other opens a track of its own.
    const std::vector<BladeObservation> obs{
        {0, straightBlade(0.f)}, {1, straightBlade(0.02f)}, {1, straightBlade(0.004f)}};
    const auto tracks = trackBlades(obs);
    ASSERT_EQ(tracks.size(), 2u);
    EXPECT_EQ(tracks[0], (std::vector<std::size_t>{0, 2}));
    EXPECT_EQ(tracks[1], (std::vector<std::size_t>{1}));
}

TEST(BladeTracks, PerGroupCaptureKeepsEveryObservationApart) {
    const std::vector<BladeObservation> obs{{0, straightBlade(0.f)}, {1, straightBlade(0.f)}};
    BladeTrackParams params;
    params.enabled = false;
    EXPECT_EQ(trackBlades(obs, params).size(), 2u);
    EXPECT_EQ(trackBlades(obs).size(), 1u);
}

TEST(BladeTracks, TheSharedRootDoesNotTellBladesApartButTheRestDoes) {
    // Identical above the first quarter, 30 mm apart below it: distance 0. A blade shifted 3 mm
    // everywhere: 3 mm. A view of the blade cut short at 70 % of its length lies along it: 0.
    const Skeleton a = straightBlade(0.f);
    Skeleton b = a;
    for (int j = 0; j < kPoints / 4; ++j) b.points_m[static_cast<std::size_t>(j)].x += 0.03f;
    EXPECT_FLOAT_EQ(skeletonDistance_m(a, b), 0.f);
    EXPECT_NEAR(skeletonDistance_m(a, straightBlade(0.f, 0.15f, {0.003f, 0.f, 0.f})), 0.003f,
                1e-6f);
    EXPECT_NEAR(skeletonDistance_m(a, straightBlade(0.f, 0.105f)), 0.f, 1e-6f);
    EXPECT_NEAR(skeletonDistance_m(straightBlade(0.f, 0.105f), a), 0.f, 1e-6f);
    Skeleton point;
    point.points_m = {a.points_m.front()};
    EXPECT_TRUE(std::isinf(skeletonDistance_m(a, point)));
}

TEST(BladeTracks, AViewCutShortOrNotRootedJoinsItsBladeButNotItsMean) {
    // Four views of one blade: two whole and rooted, one cut short at 75 %, one not rooted (its
    // skeleton starts where the blade became visible, 30 % up).
    std::vector<BladeObservation> obs{{0, straightBlade(0.f)},
                                      {1, straightBlade(0.f, 0.1125f)},
                                      {2, straightBlade(0.f, 0.15f, {0.001f, 0.f, 0.f})},
                                      {3, straightBlade(0.f, 0.105f, {0.f, -0.045f, 0.f})}};
    obs[3].skeleton.baseNotRooted = true;
    const auto tracks = trackBlades(obs);
    ASSERT_EQ(tracks.size(), 1u);
    EXPECT_EQ(tracks[0], (std::vector<std::size_t>{0, 1, 2, 3}));
    EXPECT_EQ(membersForMean(obs, tracks[0]), (std::vector<std::size_t>{0, 2}));
    EXPECT_EQ(trackSkeleton(obs, tracks[0]).points_m,
              meanSkeleton({&obs[0].skeleton, &obs[2].skeleton}).points_m);
    // A track of one, or of views all cut alike, keeps them all.
    EXPECT_EQ(membersForMean(obs, {1}), (std::vector<std::size_t>{1}));
    EXPECT_EQ(membersForMean(obs, {0, 2}), (std::vector<std::size_t>{0, 2}));
}

TEST(BladeTracks, TheMeanSkeletonAveragesPointsWidthsAndAddedPieces) {
    Skeleton a = straightBlade(0.f, 0.15f, {}, 0.010f);
    Skeleton b = straightBlade(0.f, 0.15f, {0.002f, 0.f, 0.004f}, 0.012f);
    a.tipExtension_m = 0.010f, a.tipPoints = 8, a.reasons = {"tip extended"};
    b.tipExtension_m = 0.020f, b.tipPoints = 13, b.reasons = {"tip extended", "depth filled"};
    b.baseNotRooted = true;
    const Skeleton m = meanSkeleton({&a, &b});
    ASSERT_EQ(m.points_m.size(), a.points_m.size());
    EXPECT_NEAR(m.points_m[60].x, a.points_m[60].x + 0.001f, 1e-6f);
    EXPECT_NEAR(m.points_m[60].z, a.points_m[60].z + 0.002f, 1e-6f);
    EXPECT_NEAR(m.width_m[0], 0.011f, 1e-6f);
    EXPECT_NEAR(m.tipExtension_m, 0.015f, 1e-6f);
    EXPECT_EQ(m.tipPoints, 11);  // 10.5 rounded
    EXPECT_FALSE(m.baseNotRooted) << "one of two is no majority";
    EXPECT_EQ(m.reasons, (std::vector<std::string>{"tip extended", "depth filled"}));
    EXPECT_FLOAT_EQ(glm::length(m.across_px[5]), 1.f);

    const Skeleton one = meanSkeleton({&b});
    EXPECT_EQ(one.points_m, b.points_m);
    EXPECT_TRUE(one.baseNotRooted);
    Skeleton shorter = a;
    shorter.points_m.pop_back();
    shorter.width_m.pop_back();
    EXPECT_THROW(meanSkeleton({&a, &shorter}), std::invalid_argument);
    EXPECT_THROW(meanSkeleton({}), std::invalid_argument);
}

}  // namespace
}  // namespace meadow::modeling
