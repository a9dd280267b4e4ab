// Skeleton by symmetric contour matching, on synthetic blades with known truth.
#include "meadow/modeling/skeleton.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>

#include "meadow/modeling/error.h"
#include "modeling/blade_fit_synthetic_test.h"

namespace meadow::modeling {
namespace {

using test::fineIntrinsics;
using test::makeBlade;
using test::renderBlade;

// A slim blade 0.12 m tall tilted in depth, for the thin-tip tests, with a wall this far away.
constexpr float kSlimBladeWall_m = 0.9f;
test::SyntheticBlade slimTiltedBlade() {
    return makeBlade({0.f, 0.08f, 0.5f}, 0.12f, 0.2f, 0.004f, 0.3f);
}
// The image row `fraction` of the blade's image height below its tip.
float rowBelowTip(const test::SyntheticBlade& b, float fraction) {
    const float tipRow =
        fineIntrinsics().project(b.spine_m.at(b.spine_m.parameterAtLengthFraction(1.f))).y;
    const float baseRow = fineIntrinsics().project(b.spine_m.v0).y;
    return tipRow + fraction * (baseRow - tipRow);
}

TEST(Skeleton, ResampleByArcLengthKeepsEndsAndSpacesEvenly) {
    const std::vector<glm::vec2> line{{0, 0}, {1, 0}, {1, 3}};  // length 4
    const auto r = resampleByArcLength(line, 5);
    ASSERT_EQ(r.size(), 5u);
    EXPECT_EQ(r.front(), line.front());
    EXPECT_EQ(r.back(), line.back());
    for (std::size_t i = 1; i < r.size(); ++i)
        EXPECT_NEAR(glm::distance(r[i - 1], r[i]), 1.f, 1e-5f) << "i " << i;
    EXPECT_THROW(resampleByArcLength(line, 1), std::invalid_argument);
}

TEST(Skeleton, StraightBladeOfConstantWidthHasCentredMidlineAndFullWidth) {
    // Pixel boundary of a 9-pixel-wide vertical strip, x = 10..18, rows 5..60, base at the
    // bottom: side A goes up x = 10, the tip row is y = 5, side B comes down x = 18.
    capture::BladeContour blade;
    for (int y = 60; y >= 5; --y) blade.contour_px.emplace_back(10, y);
    for (int x = 11; x <= 17; ++x) blade.contour_px.emplace_back(x, 5);
    blade.tipIndex = static_cast<int>(blade.contour_px.size()) - 4;  // x = 14, the middle
    for (int y = 5; y <= 60; ++y) blade.contour_px.emplace_back(18, y);
    SkeletonParams params;
    params.points = 33;
    const Skeleton s = matchSymmetricContour(blade, params);
    ASSERT_EQ(s.midline_px.size(), 33u);
    for (std::size_t i = 0; i + 6 < s.midline_px.size(); ++i) {  // the flat tip row is not a side
        EXPECT_NEAR(s.midline_px[i].x, 14.f, 1e-4f) << "i " << i;
        EXPECT_NEAR(s.width_px[i], 9.f, 0.6f) << "i " << i;  // 8 between centres + 1 pixel
    }
    EXPECT_NEAR(s.sideLengthRatio, 1.f, 1e-5f);
    EXPECT_FALSE(s.asymmetric);
    EXPECT_EQ(s.width_px.back(), 0.f);
}

TEST(Skeleton, RecoversSyntheticBladeWithinHalfAMillimetreWithoutNoise) {
    const auto truth = makeBlade({0.01f, 0.08f, 0.5f}, 0.12f, 0.35f, 0.006f, 0.3f);
    const auto view = renderBlade(truth, fineIntrinsics(), 0.8f);
    const Skeleton s = extractSkeleton(view.blade, view.frame);
    ASSERT_EQ(s.points_m.size(), 128u);
    const float worst_m = test::maxDistanceToSpine_m(s.points_m, truth.spine_m);
    EXPECT_LT(worst_m, 0.5e-3f) << "worst skeleton distance " << worst_m * 1e3f << " mm";
    EXPECT_LT(glm::distance(s.points_m.front(), truth.spine_m.v0), 1e-3f);
    EXPECT_LT(glm::distance(s.points_m.back(), truth.spine_m.v2), 1e-3f);
    EXPECT_FALSE(s.asymmetric) << (s.reasons.empty() ? "" : s.reasons.front());
    EXPECT_EQ(s.filledDepths, 0);
    // Widths against truth at each point's arc fraction (interior: the tip is sub-pixel).
    double sum = 0.0;
    int used = 0;
    for (std::size_t i = 0; i < s.width_m.size(); ++i) {
        if (s.arcFraction[i] > 0.95f) continue;
        sum += std::abs(s.width_m[i] - truth.width(s.arcFraction[i]));
        ++used;
    }
    EXPECT_LT(sum / used, 0.05 * truth.maxWidth_m) << "width MAE " << sum / used * 1e3 << " mm";
}

TEST(Skeleton, DistanceTransformWidthAgreesWithMatchedWidth) {
    const auto truth = makeBlade({0.f, 0.08f, 0.5f}, 0.12f, 0.2f, 0.006f);
    const auto view = renderBlade(truth, fineIntrinsics());
    const Skeleton s = matchSymmetricContour(view.blade);
    const std::vector<float> dt = distanceTransformWidth_px(view.blade.mask, s.midline_px);
    ASSERT_EQ(dt.size(), s.width_px.size());
    for (std::size_t i = 10; i + 20 < dt.size(); ++i)
        EXPECT_NEAR(dt[i], s.width_px[i], 1.0f) << "i " << i << " of " << dt.size();
    EXPECT_LT(s.ridgeOffsetFraction, 0.1f);
}

TEST(Skeleton, FlagsAsymmetricMatchWhenTheTipIsMisplaced) {
    const auto truth = makeBlade({0.f, 0.08f, 0.5f}, 0.12f, 0.2f, 0.006f);
    auto view = renderBlade(truth, fineIntrinsics());
    view.blade.tipIndex = view.blade.tipIndex / 2;  // sides now differ by a factor ~3
    const Skeleton s = matchSymmetricContour(view.blade);
    EXPECT_TRUE(s.asymmetric);
    EXPECT_GT(s.sideLengthRatio, 2.f);
    EXPECT_FALSE(s.reasons.empty());
}

TEST(Skeleton, IgnoresHolesAndFlyingPixelsInDepth) {
    const auto truth = makeBlade({0.f, 0.08f, 0.5f}, 0.12f, 0.3f, 0.006f);
    auto view = renderBlade(truth, fineIntrinsics(), 0.9f);
    cv::Mat1w& depth = view.frame.depth_mm;
    // A hole across the whole blade a third of the way up, and flying pixels (halfway to the
    // background) on every other edge pixel of the mask.
    const glm::vec2 mid = fineIntrinsics().project(truth.spine_m.at(0.33f));
    cv::rectangle(depth, cv::Rect(static_cast<int>(mid.x) - 20, static_cast<int>(mid.y) - 4, 40, 8),
                  cv::Scalar(0), cv::FILLED);
    cv::Mat1b eroded;
    cv::erode(view.blade.mask, eroded, cv::Mat());
    int k = 0;
    for (int v = 0; v < depth.rows; ++v)
        for (int u = 0; u < depth.cols; ++u)
            if (view.blade.mask(v, u) && !eroded(v, u) && depth(v, u) > 0 && (k++ % 2 == 0))
                depth(v, u) = static_cast<std::uint16_t>((depth(v, u) + 900) / 2);
    const Skeleton s = extractSkeleton(view.blade, view.frame);
    const float worst_m = test::maxDistanceToSpine_m(s.points_m, truth.spine_m);
    EXPECT_LT(worst_m, 1e-3f) << "worst skeleton distance " << worst_m * 1e3f << " mm";
    EXPECT_GT(s.filledDepths, 0);
}

TEST(Skeleton, ThinTipWhoseLastReadingsFlyTowardTheWallStaysOnTheBlade) {
    // A slim blade tilted in depth, a wall 0.4 m behind it. The last 13 % of the blade (by
    // height in the image) reads flying pixels: depths between the blade and the wall, as a
    // Kinect reads a tip narrower than its resolution. Every reading there flies, so a running
    // median along the chain is itself a flying pixel at the tip; the skeleton's tip must stay
    // within 3 mm of the true tip depth all the same.
    constexpr float kFlyingFraction = 0.13f, kWall_m = kSlimBladeWall_m, kTolerance_m = 3e-3f;
    const auto truth = slimTiltedBlade();
    auto view = renderBlade(truth, fineIntrinsics(), kWall_m);
    cv::Mat1w& depth = view.frame.depth_mm;
    const float flyingBelowRow = rowBelowTip(truth, kFlyingFraction);
    cv::RNG rng(7);
    int flying = 0;
    for (int v = 0; v < depth.rows; ++v)
        for (int u = 0; u < depth.cols; ++u)
            if (view.blade.mask(v, u) && static_cast<float>(v) < flyingBelowRow) {
                const float t = static_cast<float>(rng.uniform(0.2, 0.9));
                const float blade_mm = depth(v, u);
                depth(v, u) = static_cast<std::uint16_t>(
                    std::lround(blade_mm + t * (kWall_m * 1e3f - blade_mm)));
                ++flying;
            }
    ASSERT_GT(flying, 50);
    const Skeleton s = extractSkeleton(view.blade, view.frame);
    EXPECT_NEAR(s.depth_m.back(), truth.spine_m.v2.z, kTolerance_m)
        << "tip depth " << s.depth_m.back() << " m, true " << truth.spine_m.v2.z << " m, wall "
        << kWall_m << " m, " << flying << " flying pixels above row " << flyingBelowRow;
    EXPECT_LT(glm::distance(s.points_m.back(), truth.spine_m.v2), kTolerance_m)
        << "tip " << s.points_m.back().x << ", " << s.points_m.back().y << ", "
        << s.points_m.back().z << " true " << truth.spine_m.v2.x << ", " << truth.spine_m.v2.y
        << ", " << truth.spine_m.v2.z;
    EXPECT_GT(s.filledDepths, 0);
}

TEST(Skeleton, ReadingsOutsideTheTuftsDepthRangeAreNotTheBlades) {
    // The upper third of a slim blade as a tip trail leaves it: most mask pixels there are the
    // one-pixel links between dotted readings, and they read the wall 0.4 m behind. Only the
    // depth range the segmentation kept (SkeletonParams::minDepth_m / maxDepth_m) tells them
    // from the blade.
    constexpr float kWall_m = kSlimBladeWall_m, kTolerance_m = 3e-3f;
    const auto truth = slimTiltedBlade();
    auto view = renderBlade(truth, fineIntrinsics(), kWall_m);
    cv::Mat1w& depth = view.frame.depth_mm;
    const float linksBelowRow = rowBelowTip(truth, 0.33f);
    cv::RNG rng(11);
    int links = 0;
    for (int v = 0; v < depth.rows; ++v)
        for (int u = 0; u < depth.cols; ++u)
            if (view.blade.mask(v, u) && static_cast<float>(v) < linksBelowRow &&
                rng.uniform(0.f, 1.f) < 0.7f) {
                depth(v, u) = static_cast<std::uint16_t>(kWall_m * 1e3f);
                ++links;
            }
    ASSERT_GT(links, 50);
    SkeletonParams params;
    params.minDepth_m = truth.spine_m.v2.z - 0.02f;
    params.maxDepth_m = truth.spine_m.v0.z + 0.02f;
    ASSERT_LT(params.maxDepth_m, kWall_m);
    const Skeleton s = extractSkeleton(view.blade, view.frame, params);
    EXPECT_LT(glm::distance(s.points_m.back(), truth.spine_m.v2), kTolerance_m)
        << "tip depth " << s.depth_m.back() << " m, true " << truth.spine_m.v2.z << " m";
    const Skeleton unbounded = extractSkeleton(view.blade, view.frame);
    // Without the range the wall wins the windows' medians and the tip lands far off.
    EXPECT_GT(glm::distance(unbounded.points_m.back(), truth.spine_m.v2), 10.f * kTolerance_m);
}

TEST(Skeleton, ThrowsModelingErrorWithoutDepth) {
    const auto truth = makeBlade({0.f, 0.08f, 0.5f}, 0.12f, 0.2f, 0.006f);
    auto view = renderBlade(truth, fineIntrinsics());
    view.frame.depth_mm.setTo(0);
    EXPECT_THROW(extractSkeleton(view.blade, view.frame), ModelingError);
}

TEST(Skeleton, RejectsContourWithoutInteriorTip) {
    capture::BladeContour blade;
    blade.contour_px = {{0, 0}, {1, 1}, {2, 0}};
    blade.tipIndex = 0;
    EXPECT_THROW(matchSymmetricContour(blade), std::invalid_argument);
}

TEST(Skeleton, SmoothWidthsRemovesSpikeAndKeepsEnds) {
    const std::vector<float> w{1, 1, 1, 9, 1, 1, 1};
    const auto s = smoothWidths(w, 2);
    EXPECT_EQ(s.front(), 1.f);
    EXPECT_EQ(s.back(), 1.f);
    for (float x : s) EXPECT_NEAR(x, 1.f, 1e-6f);
}

}  // namespace
}  // namespace meadow::modeling
