// Spine, frame, width profile and shape fits; whole-blade fit on synthetic truth.
#include "meadow/modeling/blade_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <iostream>

#include "meadow/modeling/hausdorff.h"
#include "modeling/blade_fit_synthetic_test.h"

namespace meadow::modeling {
namespace {

using test::fineIntrinsics;
using test::makeBlade;
using test::renderBlade;

const QuadraticBezier kCurve{{0.f, 0.f, 0.f}, {0.01f, 0.06f, 0.002f}, {0.05f, 0.1f, 0.f}};

// kCurve at 41 evenly spaced parameters, both ends included.
std::vector<glm::vec3> evenSamplesOfCurve() {
    std::vector<glm::vec3> pts;
    for (int i = 0; i <= 40; ++i) pts.push_back(kCurve.at(static_cast<float>(i) / 40.f));
    return pts;
}

TEST(BladeFit, MiddleControlPointClosedFormIsExactForExactParameters) {
    std::vector<glm::vec3> pts;
    std::vector<float> t;
    for (int i = 0; i <= 10; ++i) t.push_back(i / 10.f), pts.push_back(kCurve.at(i / 10.f));
    const glm::vec3 v1 = leastSquaresMiddleControlPoint(pts, t, kCurve.v0, kCurve.v2);
    EXPECT_LT(glm::distance(v1, kCurve.v1), 1e-6f);
}

// The spine fit's first guess honours the point weights: a point of weight 0 (an added root
// piece's or tip extension's inner point) does not pull it.
TEST(BladeFit, MiddleControlPointClosedFormLeavesOutPointsOfWeightZero) {
    std::vector<glm::vec3> pts;
    std::vector<float> t, weights;
    for (int i = 0; i <= 10; ++i)
        t.push_back(i / 10.f), pts.push_back(kCurve.at(i / 10.f)), weights.push_back(1.f);
    pts[5] += glm::vec3(0.02f, 0.f, 0.f);
    EXPECT_GT(
        glm::distance(leastSquaresMiddleControlPoint(pts, t, kCurve.v0, kCurve.v2), kCurve.v1),
        5e-3f);
    weights[5] = 0.f;
    EXPECT_LT(glm::distance(leastSquaresMiddleControlPoint(pts, t, kCurve.v0, kCurve.v2, weights),
                            kCurve.v1),
              1e-6f);
}

TEST(BladeFit, NewtonReparameterisationRecoversCurveFromUnevenSamples) {
    std::vector<glm::vec3> pts;
    for (int i = 0; i <= 40; ++i) {
        const float u = i / 40.f;
        pts.push_back(
            kCurve.at(u * u * (3.f - 2.f * u)));  // uneven spacing: chord params are wrong
    }
    const SpineFit fit = fitQuadraticBezier(pts);
    EXPECT_LT(glm::distance(fit.spine_m.v1, kCurve.v1), 2e-5f)
        << "v1 " << fit.spine_m.v1.x << "," << fit.spine_m.v1.y;
    EXPECT_LT(fit.rms_m, 1e-5f);
    EXPECT_THROW(fitQuadraticBezier({{0, 0, 0}, {1, 0, 0}}), std::invalid_argument);
    // The free tip recovers the same curve. (Projecting the last point's residual as the
    // interior ones are let the tip retract for free: v1 came out 0.44 mm off here.)
    const SpineFit free = fitQuadraticBezier(pts, 20, SpineEnds::RootAtFirstPoint);
    EXPECT_LT(glm::distance(free.spine_m.v1, kCurve.v1), 2e-5f);
    EXPECT_LT(glm::distance(free.spine_m.v2, kCurve.v2), 2e-5f);
    EXPECT_LT(free.rms_m, 1e-5f);
}

// An exact sampling of kCurve with its first or last point moved by `offset`, fitted with that
// end pinned to the point and with it fitted (the other end as the default fit has it).
struct OffsetEndFits {
    SpineFit pinned, fitted;
};
OffsetEndFits fitsWithOffsetEnd(bool lastPoint, glm::vec3 offset) {
    std::vector<glm::vec3> pts = evenSamplesOfCurve();
    (lastPoint ? pts.back() : pts.front()) += offset;
    return {
        fitQuadraticBezier(pts, 20,
                           lastPoint ? SpineEnds::AtEndPoints : SpineEnds::RootAtFirstPoint),
        fitQuadraticBezier(pts, 20, lastPoint ? SpineEnds::RootAtFirstPoint : SpineEnds::Fitted)};
}

TEST(BladeFit, AFittedTipAveragesAnOffsetLastPointThatAFixedTipTakesWhole) {
    // A skeleton's last point is its least certain (a tip 1-3 px wide): 2 mm off the curve here,
    // across it, on an otherwise exact sampling.
    const auto [fixed, free] = fitsWithOffsetEnd(true, {0.f, 0.f, 0.002f});
    EXPECT_NEAR(glm::distance(fixed.spine_m.v2, kCurve.v2), 0.002f, 1e-6f);
    // Well under the offset: the other 40 points hold the curve, and v1 and v2 share the pull.
    EXPECT_LT(glm::distance(free.spine_m.v2, kCurve.v2), 0.0006f);
    EXPECT_LT(free.rms_m, fixed.rms_m);
}

TEST(BladeFit, AFittedRootAveragesAnOffsetFirstPoint) {
    // The skeleton's first point is the tuft's one base point; a blade's own root lies a few
    // millimetres from it. Here it is 3 mm off, sideways, on an otherwise exact sampling.
    const auto [pinned, fitted] = fitsWithOffsetEnd(false, {0.003f, 0.f, 0.f});
    EXPECT_NEAR(glm::distance(pinned.spine_m.v0, kCurve.v0), 0.003f, 1e-6f);
    // With both ends free the curve gives the offset point about a third of it.
    EXPECT_LT(glm::distance(fitted.spine_m.v0, kCurve.v0), 0.0015f);
    EXPECT_LT(glm::distance(fitted.spine_m.v2, kCurve.v2), 0.0005f);
    EXPECT_LT(fitted.rms_m, pinned.rms_m);
    // Exact samples: nothing to move.
    const SpineFit exact = fitQuadraticBezier(evenSamplesOfCurve(), 20, SpineEnds::Fitted);
    EXPECT_LT(glm::distance(exact.spine_m.v0, kCurve.v0), 2e-5f);
    EXPECT_LT(glm::distance(exact.spine_m.v1, kCurve.v1), 2e-5f);
    EXPECT_LT(glm::distance(exact.spine_m.v2, kCurve.v2), 2e-5f);
}

TEST(BladeFit, PointsOfWeightZeroDoNotShapeTheSpine) {
    // The skeleton's root piece is a straight guess from the tuft's base up to the blade: here
    // its stand-ins, points 1-8, sit 5 mm off the curve. Left out, they do not bend the spine.
    std::vector<glm::vec3> pts = evenSamplesOfCurve();
    std::vector<float> weights(pts.size(), 1.f);
    for (int i = 1; i <= 8; ++i) pts[i].x += 0.005f, weights[i] = 0.f;
    const SpineFit all = fitQuadraticBezier(pts, 20, SpineEnds::RootAtFirstPoint);
    const SpineFit measured = fitQuadraticBezier(pts, 20, SpineEnds::RootAtFirstPoint, weights);
    EXPECT_GT(glm::distance(all.spine_m.v1, kCurve.v1), 1e-3f);
    EXPECT_LT(glm::distance(measured.spine_m.v1, kCurve.v1), 2e-5f);
    EXPECT_LT(glm::distance(measured.spine_m.v2, kCurve.v2), 2e-5f);
    EXPECT_LT(measured.rms_m, 1e-5f);  // over the points that count
    EXPECT_EQ(measured.t.size(), pts.size());
    EXPECT_THROW(fitQuadraticBezier(pts, 20, SpineEnds::RootAtFirstPoint, {1.f, 1.f}),
                 std::invalid_argument);
}

TEST(BladeFit, TheSpineKeepsToWhatWasSeenBetweenTheRootPieceAndTheTipExtension) {
    // A skeleton whose first 10 and last 6 points are added pieces (rootPoints / tipPoints count
    // the piece's end, the base or the new tip, too), bent 4 mm off the true curve: the spine
    // comes from the points between and the two ends.
    Skeleton s;
    for (int i = 0; i <= 60; ++i) {
        s.points_m.push_back(kCurve.at(i / 60.f));
        s.width_m.push_back(0.004f);
    }
    s.rootPoints = 10;
    s.tipPoints = 6;
    for (int i = 1; i < 10; ++i) s.points_m[i].z += 0.004f;
    for (int i = 55; i < 60; ++i) s.points_m[i].z -= 0.004f;
    BladeFitParams params;
    params.refinedKnots = 0;
    const BladeFit seen = fitArchetype(s, params);
    EXPECT_LT(glm::distance(seen.spineCamera_m.v1, kCurve.v1), 1e-4f);
    EXPECT_LT(glm::distance(seen.spineCamera_m.v2, kCurve.v2), 1e-4f);
    params.fitSpineToAddedPieces = true;
    const BladeFit all = fitArchetype(s, params);
    EXPECT_GT(glm::distance(all.spineCamera_m.v1, kCurve.v1), 5e-4f);
}

TEST(BladeFit, LocalFrameHasRootAtOriginBaseTangentAlongYAndBendTowardPlusX) {
    // Camera-space blade growing up the image (-y) and bending toward -x.
    const QuadraticBezier cam{{0.1f, 0.1f, 0.6f}, {0.1f, 0.04f, 0.6f}, {0.06f, 0.0f, 0.61f}};
    const BladeFrame f = bladeLocalFrame(cam, {1.f, 0.f, 0.f});
    const glm::vec3 v0 = f.toLocal(cam.v0), v1 = f.toLocal(cam.v1), v2 = f.toLocal(cam.v2);
    EXPECT_LT(glm::length(v0), 1e-6f);
    EXPECT_NEAR(v1.x, 0.f, 1e-6f);
    EXPECT_NEAR(v1.z, 0.f, 1e-6f);
    EXPECT_GT(v1.y, 0.f);
    EXPECT_GT(v2.x, 0.f);
    EXPECT_NEAR(v2.z, 0.f, 1e-6f);
    const QuadraticBezier local{v0, v1, v2};
    EXPECT_NEAR(local.length(), cam.length(), 1e-6f);
    EXPECT_LT(glm::distance(f.toCamera(v2), cam.v2), 1e-6f);
}

TEST(BladeFit, WidthProfileReproducesPiecewiseLinearWidthAndToleranceTakesFewestSamples) {
    std::vector<float> s, w;
    for (int i = 0; i <= 200; ++i) s.push_back(i / 200.f), w.push_back(0.004f * (1.f - s.back()));
    const WidthProfile p16 = fitWidthProfile(s, w, 16);
    ASSERT_EQ(p16.width_m.size(), 16u);
    EXPECT_LT(widthProfileMae_m(p16, s, w), 1e-6f);
    const WidthProfile p2 = fitWidthProfile(s, w, 2);
    EXPECT_NEAR(p2.width_m[0], 0.004f, 1e-6f);
    EXPECT_NEAR(p2.width_m[1], 0.f, 1e-6f);
    EXPECT_THROW(fitWidthProfile(s, w, 1), std::invalid_argument);
}

TEST(BladeFit, NearestAnalyticShapeRecognisesEachShapeAndTau) {
    struct Case {
        AnalyticShape shape;
        float tau;
    };
    for (const Case c :
         {Case{AnalyticShape::Quad, 0.5f}, Case{AnalyticShape::Triangle, 0.5f},
          Case{AnalyticShape::Quadratic, 0.5f}, Case{AnalyticShape::TriangleTip, 0.7f}}) {
        WidthProfile p;
        for (int i = 0; i < 21; ++i)
            p.width_m.push_back(0.005f * analyticShapeWidthFraction(c.shape, i / 20.f, c.tau));
        const ShapeFit fit = nearestAnalyticShape(p);
        EXPECT_EQ(fit.shape, c.shape) << "shape " << static_cast<int>(c.shape);
        EXPECT_NEAR(fit.baseWidth_m, 0.005f, 1e-6f);
        EXPECT_LT(fit.error_m, 1e-7f);
        if (c.shape == AnalyticShape::TriangleTip) {
            EXPECT_NEAR(fit.tau, c.tau, 0.011f);
        }
    }
}

TEST(BladeFit, RecoversSyntheticBladeTipHeightAndWidthWithoutNoise) {
    for (const float bend : {0.f, 0.3f, 0.6f}) {
        const auto truth = makeBlade({0.02f, 0.09f, 0.5f}, 0.12f, bend, 0.006f, 0.2f);
        const auto view = renderBlade(truth, fineIntrinsics(), 0.9f);
        const BladeFit fit = fitBlade(
            view.blade, view.frame, {},
            {.recording = "synthetic", .frame = 3, .bladeId = 7, .flags = {}, .seenIn = {}});
        const Archetype& a = fit.archetype;
        const float tipError_mm = glm::distance(fit.spineCamera_m.v2, truth.spine_m.v2) * 1e3f;
        const float heightError =
            std::abs(a.height_m() - truth.spine_m.length()) / truth.spine_m.length();
        double widthSum = 0.0;
        for (int i = 0; i <= 100; ++i)
            widthSum += std::abs(a.width.at(i / 100.f) - truth.width(i / 100.f));
        const float widthMae = static_cast<float>(widthSum / 101.0);
        EXPECT_LE(tipError_mm, 1.f) << "bend " << bend;
        EXPECT_LE(heightError, 0.01f) << "bend " << bend << " height " << a.height_m();
        EXPECT_LE(widthMae, 0.1f * truth.maxWidth_m)
            << "bend " << bend << " width MAE " << widthMae * 1e3f << " mm";
        // Local frame and report.
        EXPECT_LT(glm::length(a.spine_m.v0), 1e-7f);
        EXPECT_GE(a.spine_m.v2.x, 0.f);
        EXPECT_GT(a.spine_m.v2.y, 0.f);
        EXPECT_LT(a.fit.spineRms_mm, 0.3f) << "bend " << bend;
        EXPECT_GT(a.fit.skeletonPoints, 100);
        EXPECT_FALSE(a.fit.asymmetric);
        EXPECT_LT(a.fit.widthCheckMae_mm, 0.1f * truth.maxWidth_m * 1e3f);
        EXPECT_EQ(a.width.width_m.size(), 16u);
        ASSERT_EQ(a.knots_m.size(), 16u);
        EXPECT_LT(glm::length(a.knots_m.front()), 1e-3f);
        EXPECT_LT(glm::distance(a.knots_m.back(), a.spine_m.v2), 1e-3f);
        EXPECT_EQ(a.source.recording, "synthetic");
        EXPECT_EQ(a.source.frame, 3);
        EXPECT_EQ(a.source.bladeId, 7);
        EXPECT_EQ(a.nearestShape, AnalyticShape::Quadratic) << "bend " << bend;  // 1 - 0.85 s^2
    }
}

TEST(BladeFit, WidthToleranceGivesFewerSamplesForSimpleShape) {
    const auto truth = makeBlade({0.f, 0.09f, 0.5f}, 0.12f, 0.2f, 0.006f);
    const auto view = renderBlade(truth, fineIntrinsics());
    BladeFitParams params;
    params.widthTolerance_m = 0.2e-3f;
    const BladeFit fit = fitBlade(view.blade, view.frame, params);
    EXPECT_LT(fit.archetype.width.width_m.size(), 16u);
    EXPECT_GE(fit.archetype.width.width_m.size(), 2u);
    EXPECT_LE(fit.archetype.fit.widthMae_mm, 0.2f);
}

// `meadow capture --tolerance-mm` and the trade-off bench set both tolerances through one call.
TEST(BladeFit, OneToleranceSetsTheWidthAndTheKnotTolerance) {
    BladeFitParams params;
    params.setTolerance_m(0.5e-3f);
    EXPECT_FLOAT_EQ(params.widthTolerance_m, 0.5e-3f);
    EXPECT_FLOAT_EQ(params.knotTolerance_m, 0.5e-3f);
    params.setTolerance_m(-1.f);  // off, as --tolerance-mm 0
    EXPECT_EQ(params.widthTolerance_m, 0.f);
    EXPECT_EQ(params.knotTolerance_m, 0.f);
}

// Under a knot tolerance the refiner keeps the fewest knots whose polyline stays within it of
// every skeleton knot over the simulated frames: fewer for a looser tolerance, two for a loose
// one, the most allowed (refinedKnots) for one no refining can meet, and the rest pose within the
// tolerance.
TEST(BladeFit, KnotToleranceKeepsTheFewestKnotsThatStayWithinIt) {
    const auto truth = makeBlade({0.f, 0.09f, 0.5f}, 0.15f, 0.6f, 0.008f);
    const auto view = renderBlade(truth, fineIntrinsics());
    const auto knotsWithin = [&](float tolerance_m) {
        BladeFitParams params;
        params.refinedKnots = 64;
        params.knotTolerance_m = tolerance_m;
        const BladeFit fit = fitBlade(view.blade, view.frame, params);
        // The rest pose: every skeleton point (blade-local) near the knots' polyline.
        float deviation = 0.f;
        const auto& k = fit.archetype.knots_m;
        for (const glm::vec3& p : fit.skeleton.points_m) {
            const glm::vec3 q = fit.frame.toLocal(p);
            float nearest = 1e9f;
            for (std::size_t i = 0; i + 1 < k.size(); ++i)
                nearest = std::min(nearest, pointSegmentDistance_m(q, k[i], k[i + 1]));
            deviation = std::max(deviation, nearest);
        }
        if (tolerance_m < 0.1f && k.size() < 64u) {
            EXPECT_LE(deviation, tolerance_m) << k.size() << " knots";
        }
        return k.size();
    };
    // The tighter the tolerance, the more knots, up to the cap of 64.
    const std::size_t loose = knotsWithin(8e-3f), tight = knotsWithin(2e-3f);
    EXPECT_GE(loose, 3u) << "a bent blade needs more than its two ends at 8 mm";
    EXPECT_LT(loose, tight);
    EXPECT_LT(tight, 64u);
    EXPECT_EQ(knotsWithin(1.f), 2u);
    EXPECT_EQ(knotsWithin(1e-7f), 64u);
}

}  // namespace
}  // namespace meadow::modeling
