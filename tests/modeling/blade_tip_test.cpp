// Continuing a segmented blade past its visible tip (blade_tip.h), on synthetic skeletons whose
// upper part is cut off, as a thin tip falls below the sensor's resolution.
#include "meadow/modeling/blade_tip.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "meadow/capture/segmenter.h"
#include "meadow/modeling/blade_fit.h"
#include "modeling/blade_fit_synthetic_test.h"

namespace meadow::modeling {
namespace {

// A straight blade 0.12 m long, leaning toward the camera and sideways, 6 mm wide at its base.
constexpr float kHeight_m = 0.12f;
constexpr float kBaseWidth_m = 0.006f;
const glm::vec3 kRoot_m{0.01f, 0.08f, 0.5f};
const glm::vec3 kDirection = glm::normalize(glm::vec3(0.3f, -1.f, -0.2f));
constexpr int kPoints = 128;
// The last 3 % of the visible chain falls to 0 width, as the contour closes and the smoothing
// pulls the widths there down whatever the blade does (skeleton.cpp).
constexpr float kClosingFraction = 0.03f;

glm::vec3 truePoint(float arc_m) { return kRoot_m + arc_m * kDirection; }

// The skeleton of the blade's part from its root up to `visibleFraction` of its length, with
// width(arc) from `width`, a +-2 % ripple and the closing drop at the visible tip.
template <class WidthFn>
Skeleton cutSkeleton(float visibleFraction, WidthFn width) {
    const capture::Intrinsics K = test::fineIntrinsics();
    Skeleton s;
    const float visible_m = visibleFraction * kHeight_m;
    for (int i = 0; i < kPoints; ++i) {
        const float f = static_cast<float>(i) / static_cast<float>(kPoints - 1);
        const float arc_m = f * visible_m;
        const glm::vec3 p = truePoint(arc_m);
        const float closing = std::min(1.f, (1.f - f) / kClosingFraction);
        const float w_m = width(arc_m) * (1.f + 0.02f * std::sin(37.f * f)) * closing;
        s.points_m.push_back(p);
        s.midline_px.push_back(K.project(p));
        s.across_px.push_back({1.f, 0.f});
        s.width_m.push_back(w_m);
        s.width_px.push_back(w_m * K.fx_px / p.z);
        s.depth_m.push_back(p.z);
        s.arcFraction.push_back(f);
    }
    return s;
}

float triangle_m(float arc_m) { return kBaseWidth_m * (1.f - arc_m / kHeight_m); }

// Cut at 92 %: the missing 8 % is within the default cap (0.1 of the visible length).
TEST(BladeTip, TaperedBladeCutAt92PercentIsExtendedToWithinOneMillimetreOfItsTrueTip) {
    Skeleton s = cutSkeleton(0.92f, triangle_m);
    extendSkeletonTip(s);
    ASSERT_EQ(s.points_m.size(), static_cast<std::size_t>(kPoints));
    EXPECT_EQ(s.width_m.size(), s.points_m.size());
    EXPECT_EQ(s.width_px.size(), s.points_m.size());
    EXPECT_EQ(s.midline_px.size(), s.points_m.size());
    EXPECT_EQ(s.depth_m.size(), s.points_m.size());
    EXPECT_LT(glm::distance(s.points_m.front(), kRoot_m), 1e-6f);
    EXPECT_LT(glm::distance(s.points_m.back(), truePoint(kHeight_m)), 1e-3f)
        << "extension " << s.tipExtension_m * 1e3f << " mm, true 9.6 mm";
    EXPECT_NEAR(s.tipExtension_m, 0.08f * kHeight_m, 1e-3f);
    // About 8 % of the points lie on the added piece; the widths there follow the taper to 0.
    EXPECT_NEAR(static_cast<float>(s.tipPoints) / kPoints, 0.08f, 0.02f);
    EXPECT_EQ(s.width_m.back(), 0.f);
    for (int i = kPoints - s.tipPoints; i < kPoints - 1; ++i) {
        const float arc_m = glm::distance(s.points_m[i], kRoot_m);
        EXPECT_NEAR(s.width_m[i], triangle_m(arc_m), 0.1f * kBaseWidth_m) << "point " << i;
    }
    // The fit reports the added length.
    const BladeFit fit = fitArchetype(s);
    EXPECT_NEAR(fit.archetype.fit.tipExtension_mm, s.tipExtension_m * 1e3f, 1e-3f);
    EXPECT_NEAR(fit.archetype.height_m(), kHeight_m, 1e-3f);
}

TEST(BladeTip, BladeOfConstantWidthIsNotExtended) {
    Skeleton s = cutSkeleton(0.88f, [](float) { return kBaseWidth_m; });
    const Skeleton before = s;
    extendSkeletonTip(s);
    EXPECT_EQ(s.tipExtension_m, 0.f);
    EXPECT_EQ(s.tipPoints, 0);
    EXPECT_EQ(s.points_m, before.points_m);
    EXPECT_EQ(s.width_m, before.width_m);
}

TEST(BladeTip, BladeWideningTowardItsTipIsNotExtended) {
    Skeleton s = cutSkeleton(0.88f, [](float arc_m) { return kBaseWidth_m * (0.5f + arc_m); });
    extendSkeletonTip(s);
    EXPECT_EQ(s.tipExtension_m, 0.f);
}

TEST(BladeTip, ExtensionIsCappedAtItsFractionOfTheVisibleLength) {
    // Cut at half its length, the blade's trend reaches zero a whole visible length further on.
    Skeleton s = cutSkeleton(0.5f, triangle_m);
    TipParams params;
    extendSkeletonTip(s, params);
    EXPECT_NEAR(s.tipExtension_m, params.maxExtensionFraction * 0.5f * kHeight_m, 1e-4f);
}

TEST(BladeTip, IsOnByDefaultAndOnlyInFitSegmentedBladeNotInFitArchetype) {
    EXPECT_TRUE(BladeFitParams{}.tip.enabled);
    Skeleton s = cutSkeleton(0.88f, triangle_m);
    const BladeFit fit = fitArchetype(s);
    EXPECT_EQ(fit.archetype.fit.tipExtension_mm, 0.f);
    EXPECT_NEAR(fit.archetype.height_m(), 0.88f * kHeight_m, 1e-3f);
}

// A rendered blade cut off at 85 % while still 15 % of its base width (the width trend asks for
// more than any cap), as the one blade of a segmentation.
struct CutView {
    test::SyntheticView view;
    capture::Segmentation seg;
};
CutView bladeCutAt85Percent() {
    auto blade = test::makeBlade({0.f, 0.08f, 0.5f}, kHeight_m, 0.2f, kBaseWidth_m);
    blade.width = [](float s) { return s < 0.85f ? kBaseWidth_m * (1.f - s) : 0.f; };
    CutView c{test::renderBlade(blade, test::fineIntrinsics(), 0.9f), {}};
    c.seg.blades.push_back(c.view.blade);
    return c;
}

// fitSegmentedBlade on that blade. A tip the segmenter followed along a tip trail (tipOnTrail)
// ends within a pixel or two of the true tip, so it gets the smaller cap.
TEST(BladeTip, ATipOnATrailIsExtendedLessThanACutTip) {
    auto [view, seg] = bladeCutAt85Percent();
    const TipParams defaults;
    ASSERT_LT(defaults.maxExtensionOnTrail, defaults.maxExtensionFraction);

    const BladeFit cut = fitSegmentedBlade(seg, 0, view.frame);
    seg.blades.front().tipOnTrail = true;
    const BladeFit trail = fitSegmentedBlade(seg, 0, view.frame);
    const float visible_mm = 0.85f * kHeight_m * 1e3f;
    EXPECT_NEAR(cut.archetype.fit.tipExtension_mm, defaults.maxExtensionFraction * visible_mm,
                0.05f * defaults.maxExtensionFraction * visible_mm);
    EXPECT_GT(trail.archetype.fit.tipExtension_mm, 0.f);
    EXPECT_LE(trail.archetype.fit.tipExtension_mm,
              defaults.maxExtensionOnTrail * visible_mm * 1.05f);
}

// Readings recurring over a dozen frames carry a trail to where the tip is too narrow to be read
// in enough of them; how much is still missing grows with the pixel footprint, so the extension
// is a fixed number of pixels over the blade's width in pixels.
TEST(BladeTip, ARecurringTrailTipIsExtendedByHowManyPixelsWideTheBladeIs) {
    const TipParams params;
    Skeleton s = cutSkeleton(0.9f, triangle_m);
    s.width_px.assign(s.width_px.size(), 5.f);
    ASSERT_TRUE(recurringTrailExtension(s, params));
    EXPECT_FLOAT_EQ(*recurringTrailExtension(s, params), params.extensionOnRecurringTrail_px / 5.f);
    // Seen from twice as far, half as many pixels wide: twice as far.
    Skeleton far = s;
    far.width_px.assign(far.width_px.size(), 2.5f);
    EXPECT_FLOAT_EQ(*recurringTrailExtension(far, params),
                    2.f * *recurringTrailExtension(s, params));
    // A few widths the fork inflates (the lowest 5 % of the chain, 3x) do not set it.
    Skeleton fork = s;
    for (std::size_t i = 0; i < fork.width_px.size() / 20; ++i) fork.width_px[i] = 15.f;
    EXPECT_FLOAT_EQ(*recurringTrailExtension(fork, params), *recurringTrailExtension(s, params));
    // Never more than a cut tip's cap; nothing to go by without pixel widths.
    Skeleton hair = s;
    hair.width_px.assign(hair.width_px.size(), 1.f);
    EXPECT_FLOAT_EQ(*recurringTrailExtension(hair, params), params.maxExtensionFraction);
    Skeleton noPixels = s;
    noPixels.width_px.clear();
    EXPECT_FALSE(recurringTrailExtension(noPixels, params));
}

// The extension does not wait for the widths to taper: along a trail they are the trail's own.
TEST(BladeTip, AFixedExtensionIsMadeWhateverTheWidthsDo) {
    Skeleton s = cutSkeleton(0.8f, [](float) { return kBaseWidth_m; });
    TipParams params;
    Skeleton trend = s;
    extendSkeletonTip(trend, params);
    EXPECT_EQ(trend.tipExtension_m, 0.f);
    params.fixedExtensionFraction = 0.04f;
    extendSkeletonTip(s, params);
    EXPECT_NEAR(s.tipExtension_m, 0.04f * 0.8f * kHeight_m, 1e-5f);
    EXPECT_LT(glm::distance(s.points_m.back(), truePoint(0.8f * 1.04f * kHeight_m)), 1e-4f);
    EXPECT_EQ(s.width_m.back(), 0.f);
}

// fitSegmentedBlade extends a trail tip of a segmentation with recurring readings by that rule,
// past what the width trend would give it (at most maxExtensionOnTrail of a group's own trails).
TEST(BladeTip, ATrailTipOfASegmentationWithRecurringReadingsIsExtendedByThePixelRule) {
    auto [view, seg] = bladeCutAt85Percent();
    seg.blades.front().tipOnTrail = true;
    seg.recurringFrames = 12;
    BladeFitParams untipped;
    untipped.tip.enabled = false;
    const std::optional<float> fraction =
        recurringTrailExtension(segmentedBladeSkeleton(seg, 0, view.frame, untipped));
    ASSERT_TRUE(fraction);
    const TipParams defaults;
    ASSERT_NE(*fraction, defaults.maxExtensionOnTrail);
    const float visible_mm = 0.85f * kHeight_m * 1e3f;
    const BladeFit fit = fitSegmentedBlade(seg, 0, view.frame);
    EXPECT_NEAR(fit.archetype.fit.tipExtension_mm, *fraction * visible_mm,
                0.05f * *fraction * visible_mm);
}

}  // namespace
}  // namespace meadow::modeling
