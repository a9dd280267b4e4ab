// Rooting a segmented blade at its tuft's base (blade_root.h), and the fit that uses it.
#include "meadow/modeling/blade_root.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "chain_resample.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/error.h"

namespace meadow::modeling {
namespace {

using detail::arcLengthStations;
using detail::sampleAt;

// Fraction of the chain, from its base end, whose direction is the blade's base direction for
// the "base above the blade" test.
constexpr float kBasePartFraction = 0.08f;
// The segmented contour starts at the fork, where its two sides follow the crotch between
// neighbouring blades (or, for a leaf cut from a stem, the stem and the leaves beside it): the
// matched widths over the lowest part of the chain overstate the blade's width, by up to
// several times. The widths of the part just above it (kWidthReferenceFrom to
// kWidthReferenceTo of the chain, median) bound those of the lowest part (below
// kWidthReferenceFrom), and the added piece carries that median. Every blade-type preset's true
// width at its base is at most its width there.
constexpr float kWidthReferenceFrom = 0.15f;
constexpr float kWidthReferenceTo = 0.35f;
constexpr float kMillimetresPerMetre = 1000.f;

// How a blade left unrooted is noted: the base point is the overlay's magenta diamond, where the
// tuft's blades meet or, for a potted plant, its region's foot.
constexpr const char* kNotRooted = "not rooted at the base point: ";

// Whole millimetres, for notes.
long millimetres(float metres) { return std::lround(metres * kMillimetresPerMetre); }

// Columns either side of the base point searched for the cluster's lowest pixel.
constexpr int kLowestRowHalfWidth_px = 2;

float medianOf(std::vector<float> v) {
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

// Bounds the widths of the skeleton's lowest part (below kWidthReferenceFrom) by the median of
// those just above it (kWidthReferenceFrom to kWidthReferenceTo), in pixels and metres; returns
// those medians (0 where a width list does not run along the points).
struct FlareReference {
    float px = 0.f, m = 0.f;
};
FlareReference boundBaseFlare(Skeleton& s) {
    const int n = static_cast<int>(s.points_m.size());
    const auto index = [n](float f) {
        return std::clamp(static_cast<int>(std::lround(f * static_cast<float>(n - 1))), 0, n - 1);
    };
    const int from = index(kWidthReferenceFrom), to = std::max(from, index(kWidthReferenceTo));
    const auto bound = [&](std::vector<float>& w) {
        if (w.size() != s.points_m.size() || n == 0) return 0.f;
        const float reference = medianOf(std::vector<float>(w.begin() + from, w.begin() + to + 1));
        for (int i = 0; i < from; ++i) w[i] = std::min(w[i], reference);
        return reference;
    };
    FlareReference r;
    r.px = bound(s.width_px);
    r.m = bound(s.width_m);
    return r;
}

// The cluster whose bladeIds hold `bladeId`, or null.
const capture::BladeCluster* clusterOf(const capture::Segmentation& segmentation, int bladeId) {
    const auto cluster = std::find_if(
        segmentation.clusters.begin(), segmentation.clusters.end(), [&](const auto& c) {
            return std::find(c.bladeIds.begin(), c.bladeIds.end(), bladeId) != c.bladeIds.end();
        });
    return cluster == segmentation.clusters.end() ? nullptr : &*cluster;
}

}  // namespace

bool leavesAStem(const capture::Segmentation& segmentation, int bladeId) {
    const capture::BladeCluster* cluster = clusterOf(segmentation, bladeId);
    return cluster != nullptr && !cluster->stemLine_px.empty();
}

std::optional<ClusterBase> clusterBase(const capture::Segmentation& segmentation, int bladeId,
                                       const capture::DepthFrame& frame, const RootParams& params) {
    const capture::BladeCluster* cluster = clusterOf(segmentation, bladeId);
    if (cluster == nullptr || frame.depth_mm.empty()) return std::nullopt;
    const cv::Mat1b& mask = segmentation.clusterMask;
    const bool useMask = !mask.empty() && mask.size() == frame.depth_mm.size();
    ClusterBase base;
    base.base_px = {cluster->basePoint_px.x, cluster->basePoint_px.y};
    if (useMask && params.toLowestRow) {
        // The base point is the centroid of the cluster's lowest rows, half that band above the
        // cluster's bottom; the tuft's root is at the bottom, so the base moves down to the
        // lowest cluster pixel under it (within a few columns), to that pixel's lower edge.
        // Only the run of mask pixels that continues down from the base point counts: the mask
        // holds every cluster, and a fragment lower down is not this tuft's bottom.
        const int u = static_cast<int>(std::lround(base.base_px.x));
        const int v = std::clamp(static_cast<int>(std::lround(base.base_px.y)), 0, mask.rows - 1);
        int lowest = -1;
        for (int du = -kLowestRowHalfWidth_px; du <= kLowestRowHalfWidth_px; ++du) {
            const int x = u + du;
            if (x < 0 || x >= mask.cols || mask(v, x) == 0) continue;
            int y = v;
            while (y + 1 < mask.rows && mask(y + 1, x) != 0) ++y;
            lowest = std::max(lowest, y);
        }
        if (static_cast<float>(lowest) + 0.5f > base.base_px.y)
            base.base_px.y = static_cast<float>(lowest) + 0.5f;
    }
    const int u0 = static_cast<int>(std::lround(base.base_px.x)),
              v0 = static_cast<int>(std::lround(base.base_px.y));
    std::vector<float> readings_m;
    for (int r = std::max(0, params.depthWindowRadius_px); r <= params.maxDepthWindowRadius_px;
         ++r) {
        readings_m.clear();
        for (int v = std::max(0, v0 - r); v <= std::min(frame.depth_mm.rows - 1, v0 + r); ++v)
            for (int u = std::max(0, u0 - r); u <= std::min(frame.depth_mm.cols - 1, u0 + r); ++u)
                if ((!useMask || mask(v, u) != 0) && frame.depth_mm(v, u) > 0)
                    readings_m.push_back(static_cast<float>(frame.depth_mm(v, u)) /
                                         kMillimetresPerMetre);
        if (static_cast<int>(readings_m.size()) >= params.minDepthReadings) break;
    }
    if (readings_m.empty()) return std::nullopt;
    base.depthReadings = static_cast<int>(readings_m.size());
    base.depth_m = medianOf(std::move(readings_m));
    base.base_m = frame.intrinsics.backProject(base.base_px.x, base.base_px.y, base.depth_m);
    if (params.dropToGround && segmentation.groundPlane) {
        const cv::Vec4f& g = *segmentation.groundPlane;
        const glm::vec3 up(g[0], g[1], g[2]);
        const float height_m = glm::dot(up, base.base_m) + g[3];
        if (height_m > 0.f && height_m <= params.maxGroundDrop_m) {
            base.base_m -= height_m * up;
            base.groundDrop_m = height_m;
        }
    }
    return base;
}

void rootSkeleton(Skeleton& s, const ClusterBase& base, const RootParams& params) {
    const int n = static_cast<int>(s.points_m.size());
    if (n < 3 || s.midline_px.size() != s.points_m.size() || s.width_m.size() != s.points_m.size())
        throw std::invalid_argument("rootSkeleton: need a lifted skeleton with >= 3 points");
    const float length_m = detail::polylineLength_m(s.points_m);
    const glm::vec3 lower = s.points_m.front();
    const float extension_m = glm::distance(base.base_m, lower);
    const int k = std::clamp(
        static_cast<int>(std::lround(kBasePartFraction * static_cast<float>(n - 1))), 1, n - 1);
    const glm::vec3 bladeDirection = s.points_m[static_cast<std::size_t>(k)] - lower;
    const auto refuse = [&](const std::string& why) {
        s.baseNotRooted = true;
        s.reasons.push_back(kNotRooted + why);
    };
    if (extension_m > params.maxExtensionFraction * length_m) {
        std::ostringstream why;
        why.precision(2);
        why << "it lies " << millimetres(extension_m)
            << " mm from the blade's lower end, more than " << params.maxExtensionFraction
            << " x the blade's visible length (" << millimetres(length_m) << " mm)";
        refuse(why.str());
        return;
    }
    if (glm::dot(lower - base.base_m, bladeDirection) < 0.f) {
        refuse("it lies above the blade's lower end along the blade (" +
               std::to_string(millimetres(extension_m)) + " mm away)");
        return;
    }
    s.baseExtension_m = extension_m;
    if (extension_m <= 0.f) return;

    // Widths of the fork's flare bounded, and carried down the added piece (kWidthReferenceFrom).
    const FlareReference flare = boundBaseFlare(s);
    const auto prepend = [](auto& v, auto value) { v.insert(v.begin(), value); };
    std::vector<glm::vec3> points = s.points_m;
    prepend(points, base.base_m);
    const auto stations = arcLengthStations(points, n);
    std::vector<glm::vec2> midline = s.midline_px, across = s.across_px;
    std::vector<float> width_px = s.width_px, width_m = s.width_m, depth = s.depth_m;
    std::vector<glm::vec3> acrossStep = s.acrossStep_m;
    prepend(acrossStep, glm::vec3(0.f));  // the added piece was not read
    prepend(midline, base.base_px);
    prepend(across, across.empty() ? glm::vec2(1.f, 0.f) : across.front());
    prepend(width_px, flare.px);
    prepend(width_m, flare.m);
    prepend(depth, base.base_m.z);
    // Points before the first station on the original chain lie on the added piece.
    s.rootPoints = static_cast<int>(std::count_if(stations.begin(), stations.end(),
                                                  [](const auto& st) { return st.first == 0; }));
    s.points_m = sampleAt(points, stations);
    s.points_m.front() = base.base_m;
    s.midline_px = sampleAt(midline, stations);
    if (across.size() == points.size()) {
        s.across_px = sampleAt(across, stations);
        for (glm::vec2& a : s.across_px)
            if (glm::length(a) > 0.f) a = glm::normalize(a);
    }
    if (width_px.size() == points.size()) s.width_px = sampleAt(width_px, stations);
    s.width_m = sampleAt(width_m, stations);
    if (depth.size() == points.size()) s.depth_m = sampleAt(depth, stations);
    if (acrossStep.size() == points.size()) s.acrossStep_m = sampleAt(acrossStep, stations);
    s.width_px.back() = 0.f;
    s.width_m.back() = 0.f;
    s.arcFraction.assign(static_cast<std::size_t>(n), 0.f);
    for (int i = 1; i < n; ++i)
        s.arcFraction[i] = s.arcFraction[i - 1] + glm::distance(s.points_m[i - 1], s.points_m[i]);
    const float total = s.arcFraction.back();
    // A tip extension (blade_tip.h) keeps its length; its points are counted again.
    if (s.tipPoints > 0)
        s.tipPoints = static_cast<int>(
            std::count_if(s.arcFraction.begin(), s.arcFraction.end(),
                          [&](float a_m) { return a_m > total - s.tipExtension_m; }));
    for (float& f : s.arcFraction) f = total > 0.f ? f / total : 0.f;
}

Skeleton segmentedBladeSkeleton(const capture::Segmentation& segmentation, std::size_t bladeIndex,
                                const capture::DepthFrame& frame, const BladeFitParams& params) {
    if (bladeIndex >= segmentation.blades.size())
        throw std::invalid_argument("segmentedBladeSkeleton: blade index " +
                                    std::to_string(bladeIndex) + " of " +
                                    std::to_string(segmentation.blades.size()));
    const capture::BladeContour& blade = segmentation.blades[bladeIndex];
    SkeletonParams skeletonParams = params.skeleton;
    if (skeletonParams.minDepth_m == 0.f && skeletonParams.maxDepth_m == 0.f) {
        skeletonParams.minDepth_m = segmentation.tuftNearest_m;
        skeletonParams.maxDepth_m = segmentation.tuftFarthest_m;
    }
    Skeleton skeleton = extractSkeleton(blade, frame, skeletonParams);
    if (params.tip.enabled) {
        TipParams tip = params.tip;
        if (blade.tipOnTrail) {
            if (tip.toEndOnTrail) tip.widthFitTo = 1.f;
            const std::optional<float> recurring = segmentation.recurringFrames > 0
                                                       ? recurringTrailExtension(skeleton, tip)
                                                       : std::nullopt;
            if (recurring)
                tip.fixedExtensionFraction = *recurring;
            else
                tip.maxExtensionFraction =
                    std::min(tip.maxExtensionFraction, tip.maxExtensionOnTrail);
        }
        extendSkeletonTip(skeleton, tip);
    }
    // A leaf cut where it leaves a stem (PartitionMethod::StemGraph) starts at its own base: its
    // length runs along it, not down the stem to the plant's foot. Its outline starts where it
    // meets the stem and its neighbours, so its lowest widths flare as a fork's do.
    const bool cutFromAStem = leavesAStem(segmentation, blade.id);
    if (cutFromAStem) boundBaseFlare(skeleton);
    if (params.root.enabled && !cutFromAStem) {
        if (const auto base = clusterBase(segmentation, blade.id, frame, params.root)) {
            rootSkeleton(skeleton, *base, params.root);
        } else {
            skeleton.baseNotRooted = true;
            skeleton.reasons.push_back(
                std::string(kNotRooted) + "no cluster lists the blade, or no valid depth within " +
                std::to_string(params.root.maxDepthWindowRadius_px) + " px of its base point");
        }
    }
    return skeleton;
}

BladeFit fitSegmentedBlade(const capture::Segmentation& segmentation, std::size_t bladeIndex,
                           const capture::DepthFrame& frame, const BladeFitParams& params,
                           const Source& source) {
    const Skeleton skeleton = segmentedBladeSkeleton(segmentation, bladeIndex, frame, params);
    const capture::BladeContour& blade = segmentation.blades[bladeIndex];
    Source src = source;
    if (src.frame < 0) src.frame = frame.index;
    if (src.bladeId == 0) src.bladeId = blade.id;
    return fitArchetype(skeleton, params, src, blade.mask, &frame.intrinsics, blade.maskOrigin_px);
}

}  // namespace meadow::modeling
