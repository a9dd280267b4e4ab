// The twist read from the depth across a blade (blade_fit.h, fitTwist), on reads made by hand: a
// straight blade up the local Y axis whose across steps turn by a known angle about it. A ribbon's
// width direction is a line, so each read is known up to a half turn; these are the cases where
// that matters (a blade seen edge-on, one twisted past a quarter turn) and what the fit must
// never return whatever the reads (values the library's reader refuses).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "meadow/modeling/blade_fit.h"

namespace meadow::modeling {
namespace {

constexpr int kPoints = 120;
constexpr float kPi = std::numbers::pi_v<float>;

struct Reads {
    Skeleton skeleton;
    BladeFrame frame;  // local = camera
    QuadraticBezier spine{{0.f, 0.f, 0.f}, {0.f, 0.1f, 0.f}, {0.f, 0.2f, 0.f}};
    std::vector<float> t, s;
};

// The spine runs up +Y, so W = normalize(T x Z) = +X and T x W = -Z: a face turned by theta
// steps across by cos(theta) X - sin(theta) Z. `angleAt(s)` gives theta at arc fraction s.
Reads readsOf(const std::function<float(float)>& angleAt) {
    Reads r;
    for (int j = 0; j < kPoints; ++j) {
        const float s = static_cast<float>(j) / (kPoints - 1);
        const float theta = angleAt(s);
        r.skeleton.points_m.push_back({0.f, 0.2f * s, 1.f});
        r.skeleton.acrossStep_m.push_back(0.001f *
                                          glm::vec3(std::cos(theta), 0.f, -std::sin(theta)));
        r.t.push_back(s);
        r.s.push_back(s);
    }
    return r;
}

TwistFit fit(const Reads& r) { return fitTwist(r.skeleton, r.frame, r.spine, r.t, r.s); }

TEST(BladeTwist, AFlatLeafTurnedAtAnAngleReadsThatTiltAndNoTwist) {
    const TwistFit f = fit(readsOf([](float) { return 0.6f; }));
    ASSERT_TRUE(f.measured);
    EXPECT_NEAR(f.baseTilt_rad, 0.6f, 0.01f);
    EXPECT_NEAR(f.twistAtTip_rad, 0.f, 0.01f);
}

TEST(BladeTwist, ALeafSeenEdgeOnIsNotReadAsTwistedByItsReadsFlippingSides) {
    // Edge-on (a quarter turn), read with noise: half the reads fall on each side of +-pi/2.
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.f, 0.12f);
    const TwistFit f = fit(readsOf([&](float) { return 0.5f * kPi + noise(rng); }));
    ASSERT_TRUE(f.measured);
    EXPECT_NEAR(f.twistAtTip_rad, 0.f, 0.15f);
    EXPECT_NEAR(std::abs(f.baseTilt_rad), 0.5f * kPi, 0.1f);
    EXPECT_LE(std::abs(f.baseTilt_rad), 0.5f * kPi);
}

TEST(BladeTwist, ALeafTwistedPastAQuarterTurnIsReadWithItsWholeTwist) {
    for (const float twist : {2.5f, -2.5f, 4.f}) {
        const TwistFit f = fit(readsOf([&](float s) { return 0.3f + twist * s; }));
        ASSERT_TRUE(f.measured) << "twist " << twist;
        EXPECT_NEAR(f.twistAtTip_rad, twist, 0.05f) << "twist " << twist;
        EXPECT_NEAR(f.baseTilt_rad, 0.3f, 0.05f) << "twist " << twist;
    }
}

TEST(BladeTwist, ReadsOfNoiseNeverGiveWhatALibraryCannotHold) {
    // Reads at random angles hold no face direction; and whatever the fit makes of reads, the
    // library's reader must take it back (the twist within a full turn, the base's tilt within a
    // half turn either way).
    std::uniform_real_distribution<float> anyAngle(-kPi, kPi);
    for (unsigned seed = 1; seed <= 40; ++seed) {
        std::mt19937 rng(seed);
        const TwistFit f = fit(readsOf([&](float) { return anyAngle(rng); }));
        EXPECT_FALSE(f.measured) << "seed " << seed << ": noise read as a face";
        EXPECT_LE(std::abs(f.twistAtTip_rad), kMaxTwistAtTip_rad) << "seed " << seed;
        EXPECT_LE(std::abs(f.baseTilt_rad), 0.5f * kPi) << "seed " << seed;
        for (const float facing : f.facing) EXPECT_TRUE(facing >= 0.35f && facing <= 1.f);
    }
}

}  // namespace
}  // namespace meadow::modeling
