// One blade contour to one archetype: skeleton, refined knots, spine, width profile, shape.
#include "meadow/modeling/blade_fit.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <string>

#include "meadow/modeling/error.h"
#include "meadow/modeling/hausdorff.h"

namespace meadow::modeling {
namespace {

constexpr float kMillimetresPerMetre = 1000.f;
constexpr float kDegreesPerRadian = 57.2957795f;
constexpr float kStandardGravity_mps2 = 9.81f;
// The DT width check skips this fraction of the chain at each end, where the mask is cut (base)
// or narrower than a pixel (tip) and the DT does not measure the blade's width.
constexpr float kWidthCheckMargin = 0.15f;

WidthProfile profileWithinTolerance(const std::vector<float>& s, const std::vector<float>& w,
                                    const BladeFitParams& params) {
    if (params.widthTolerance_m > 0.f) {
        for (int n = 2; n < params.widthSamples; ++n) {
            WidthProfile p = fitWidthProfile(s, w, n);
            if (widthProfileMae_m(p, s, w) <= params.widthTolerance_m) return p;
        }
    }
    return fitWidthProfile(s, w, params.widthSamples);
}

// Algorithm 1's kept knots: refinedKnots of them, or, under a knot tolerance, the fewest whose
// polyline stays within it over the simulated frames. One run of the greedy steps gives every
// count's knots (movementSimilarityDropOrder); a binary search over the count then checks the
// deviation. The count it ends on passed its check, or is refinedKnots when no count tried did.
// The deviation grows as knots go, if not strictly, so a smaller count off the search's path
// might pass too: the search finds a passing count, not always the least.
std::vector<int> keptKnots(const KnotTrajectories& frames, const BladeFitParams& params) {
    const int all = static_cast<int>(frames.front().size());
    const int most = std::min(params.refinedKnots, all);
    if (!(params.knotTolerance_m > 0.f))
        return refineByMovementSimilarity(frames, most, params.refiner);
    const std::vector<int> order = movementSimilarityDropOrder(frames, params.refiner);
    const auto within = [&](int m) {
        return maxDeviation_m(frames, keptAfterDrops(all, order, m)) <= params.knotTolerance_m;
    };
    int lo = 2, hi = most;
    while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        if (within(mid))
            hi = mid;
        else
            lo = mid + 1;
    }
    return keptAfterDrops(all, order, lo);
}

// Weight 0 on the inner points of the root piece and the tip extension unless the spine is to
// follow them (BladeFitParams::fitSpineToAddedPieces); empty (all 1) when there are none.
std::vector<float> spineWeights(const Skeleton& skeleton, const BladeFitParams& params) {
    const int n = static_cast<int>(skeleton.points_m.size());
    if (params.fitSpineToAddedPieces || (skeleton.rootPoints <= 1 && skeleton.tipPoints <= 1))
        return {};
    std::vector<float> w(static_cast<std::size_t>(n), 1.f);
    for (int j = 1; j < std::min(skeleton.rootPoints, n - 1); ++j) w[j] = 0.f;
    for (int j = std::max(1, n - skeleton.tipPoints); j < n - 1; ++j) w[j] = 0.f;
    return w;
}

}  // namespace

BladeFit fitArchetype(const Skeleton& skeleton, const BladeFitParams& params, const Source& source,
                      const cv::Mat1b& mask, const capture::Intrinsics* intrinsics,
                      cv::Point maskOrigin_px) {
    const std::vector<glm::vec3>& points = skeleton.points_m;
    if (points.size() < 3 || skeleton.width_m.size() != points.size())
        throw ModelingError("fitArchetype: blade " + std::to_string(source.bladeId) + " of frame " +
                            std::to_string(source.frame) + " has " + std::to_string(points.size()) +
                            " skeleton points (need >= 3 with widths); check the contour");
    BladeFit out;
    out.skeleton = skeleton;
    const SpineFit spine = fitQuadraticBezier(points, params.spineIterations, params.spineEnds,
                                              spineWeights(skeleton, params));
    const float length_m = spine.spine_m.length();
    if (!(length_m > 0.f))
        throw ModelingError("fitArchetype: blade " + std::to_string(source.bladeId) + " of frame " +
                            std::to_string(source.frame) +
                            " has a zero-length spine; check the contour's tip");
    out.spineCamera_m = spine.spine_m;
    const glm::vec2 across =
        skeleton.across_px.empty() ? glm::vec2(1.f, 0.f) : skeleton.across_px.front();
    out.frame = bladeLocalFrame(spine.spine_m, glm::vec3(across, 0.f));

    Archetype& a = out.archetype;
    a.spine_m = {glm::vec3(0.f), out.frame.toLocal(spine.spine_m.v1),
                 out.frame.toLocal(spine.spine_m.v2)};
    a.source = source;
    a.source.placed = true;
    const glm::mat3 cameraFromLocal = glm::transpose(out.frame.localFromCamera);
    a.source.cameraFromBlade = glm::mat4(cameraFromLocal);
    a.source.cameraFromBlade[3] = glm::vec4(out.frame.origin_m, 1.f);
    a.name = "f" + std::to_string(source.frame) + "-b" + std::to_string(source.bladeId);

    // Width profile over the fitted spine's arc length: each skeleton point sits at the arc
    // fraction of its closest spine point (robust to depth noise lengthening the polyline).
    std::vector<float> s(points.size());
    for (std::size_t j = 0; j < points.size(); ++j)
        s[j] = spine.spine_m.lengthTo(spine.t[j]) / length_m;
    // The contour shows the width foreshortened where the face turns away from the camera: the
    // twist's fitted turn scales it back to the width in the face.
    const TwistFit twist = fitTwist(skeleton, out.frame, a.spine_m, spine.t, s);
    std::vector<float> width_m = skeleton.width_m;
    for (std::size_t j = 0; j < width_m.size(); ++j) width_m[j] /= twist.facing[j];
    a.twistAtTip_rad = twist.twistAtTip_rad;
    a.width = profileWithinTolerance(s, width_m, params);
    const ShapeFit shape = nearestAnalyticShape(a.width);
    a.nearestShape = shape.shape;
    a.tau = shape.tau;

    FitReport& r = a.fit;
    r.spineRms_mm = spine.rms_m * kMillimetresPerMetre;
    r.spineMax_mm = spine.max_m * kMillimetresPerMetre;
    r.widthMae_mm = widthProfileMae_m(a.width, s, width_m) * kMillimetresPerMetre;
    for (std::size_t j = 0; j < s.size(); ++j)
        r.widthMax_mm =
            std::max(r.widthMax_mm, std::abs(a.width.at(s[j]) - width_m[j]) * kMillimetresPerMetre);
    r.twistPoints = twist.points;
    r.baseTilt_deg = twist.baseTilt_rad * kDegreesPerRadian;
    r.shapeError_mm = shape.error_m * kMillimetresPerMetre;
    r.sideLengthRatio = skeleton.sideLengthRatio;
    r.asymmetric = skeleton.asymmetric;
    r.skeletonPoints = static_cast<int>(points.size());
    r.baseExtension_mm = skeleton.baseExtension_m * kMillimetresPerMetre;
    r.baseNotRooted = skeleton.baseNotRooted;
    r.tipExtension_mm = skeleton.tipExtension_m * kMillimetresPerMetre;
    if (!mask.empty() && intrinsics != nullptr && skeleton.width_px.size() == points.size()) {
        const std::vector<float> dt_px =
            distanceTransformWidth_px(mask, skeleton.midline_px, maskOrigin_px);
        double sum = 0.0;
        int used = 0;
        for (std::size_t j = 0; j < points.size(); ++j) {
            const float f = static_cast<float>(j) / static_cast<float>(points.size() - 1);
            // Points on a rooting piece (blade_root.h) or a tip extension (blade_tip.h) have no
            // contour behind them.
            if (f < kWidthCheckMargin || f > 1.f - kWidthCheckMargin ||
                static_cast<int>(j) < skeleton.rootPoints ||
                static_cast<int>(points.size() - j) <= skeleton.tipPoints ||
                skeleton.width_px[j] <= 0.f)
                continue;
            const float metresPerPixel = skeleton.width_m[j] / skeleton.width_px[j];
            sum += std::abs(dt_px[j] - skeleton.width_px[j]) * metresPerPixel;
            ++used;
        }
        r.widthCheckMae_mm = used > 0 ? static_cast<float>(sum / used) * kMillimetresPerMetre : 0.f;
    }

    // Refined knots (Fan & Sheng 2017, Algorithm 1) on the skeleton in the blade-local frame,
    // moved by the chain simulation with gravity along -Y.
    std::vector<glm::vec3> local(points.size());
    for (std::size_t j = 0; j < points.size(); ++j) local[j] = out.frame.toLocal(points[j]);
    if (params.refinedKnots == 1)
        throw ModelingError(
            "fitArchetype: refinedKnots is 1; 0 skips refining, otherwise at least 2 knots (the "
            "blade's two ends) are kept");
    if (params.refinedKnots > 0) {
        if (params.refinedKnots >= static_cast<int>(local.size()) &&
            !(params.knotTolerance_m > 0.f)) {
            a.knots_m = local;
        } else {
            ChainSimulationParams sim = params.simulation;
            sim.up = {0.f, 1.f, 0.f};
            sim.gravity_mps2 = {0.f, -kStandardGravity_mps2, 0.f};
            const KnotTrajectories frames = simulateChain(local, sim);
            for (int k : keptKnots(frames, params)) a.knots_m.push_back(local[k]);
        }
    }
    return out;
}

BladeFit fitBlade(const capture::BladeContour& blade, const capture::DepthFrame& frame,
                  const BladeFitParams& params, const Source& source) {
    Source src = source;
    if (src.frame < 0) src.frame = frame.index;
    if (src.bladeId == 0) src.bladeId = blade.id;
    const Skeleton skeleton = extractSkeleton(blade, frame, params.skeleton);
    return fitArchetype(skeleton, params, src, blade.mask, &frame.intrinsics, blade.maskOrigin_px);
}

}  // namespace meadow::modeling
