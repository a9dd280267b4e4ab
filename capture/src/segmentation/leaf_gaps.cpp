// A leaf the sensor did not read along a stretch (an arch seen edge-on where it folds over, a
// stretch hidden behind another leaf's edge, a depth jump taken for an edge) reaches the
// partition as two or three pieces of the mask, each modelled as a leaf of its own, none of
// them whole. Where a piece's skeleton ends and another piece's skeleton ends facing it, a short
// step away in space, running on in the same direction, the leaf runs on across the gap: a
// line of the leaf's width joins the two ends, as the stem graph joins edges through a crossing
// (skeleton_graph.h). Only ends are joined, both facing each other: a leaf's tip that points
// at another leaf's side has ended there, as far as the view tells.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <numbers>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <vector>

#include "segmentation/skeleton_graph.h"
#include "segmentation/stages.h"

namespace meadow::capture::segmentation {
namespace {

// An end's direction is read this far back along its skeleton: past the end's own rounding,
// short of the leaf's curve.
constexpr int kDirectionReach_px = 10;
constexpr int kMinDirectionReach_px = 4;
// A reading for an end's depth is looked for this far around it, on the mask.
constexpr int kDepthSearch_px = 3;

struct SkeletonEnd {
    cv::Point at;
    cv::Point2f out;  // unit, pointing away from its piece
    int piece = 0;
    float halfWidth_px = 0.f;
    glm::vec3 position_m{0.f};
};

// The depth at `p`: its reading, or the nearest reading of the mask around it (0: none).
float depthNear(const cv::Mat1w& depth_mm, const cv::Mat1b& mask, cv::Point p) {
    float best = 0.f;
    int bestDistance = std::numeric_limits<int>::max();
    for (int dy = -kDepthSearch_px; dy <= kDepthSearch_px; ++dy)
        for (int dx = -kDepthSearch_px; dx <= kDepthSearch_px; ++dx) {
            const cv::Point q = p + cv::Point(dx, dy);
            if (q.x < 0 || q.y < 0 || q.x >= mask.cols || q.y >= mask.rows || !mask(q) ||
                depth_mm(q) == 0)
                continue;
            const int d = dx * dx + dy * dy;
            if (d < bestDistance) bestDistance = d, best = static_cast<float>(depth_mm(q));
        }
    return best / kMillimetresPerMetre;
}

struct Bridge {
    int a = 0, b = 0;  // ends
    float gap_m = 0.f;
};

int findSet(std::vector<int>& parent, int i) {
    while (parent[static_cast<std::size_t>(i)] != i)
        i = parent[static_cast<std::size_t>(i)] =
            parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
}

}  // namespace

int bridgeLeafGaps(cv::Mat1b& mask, const cv::Mat1w& depth_mm, const Intrinsics& k,
                   const SegmenterParams& params, StageReport& report) {
    if (!(params.leafGapBridge_m > 0.f) || depth_mm.empty()) return 0;
    const cv::Rect box = cv::boundingRect(mask);
    if (box.empty()) return 0;
    // One pixel of margin, so that a piece at the box's edge keeps its ends.
    const cv::Rect region = (box + cv::Size(2, 2) - cv::Point(1, 1)) & cv::Rect({}, mask.size());
    const cv::Mat1b local = mask(region);
    cv::Mat1i pieces;
    const int count = cv::connectedComponents(local, pieces, 8, CV_32S);
    if (count < 3) return 0;  // background and one piece: nothing to join
    cv::Mat1b skeleton;
    cv::ximgproc::thinning(local, skeleton, cv::ximgproc::THINNING_ZHANGSUEN);
    // A rounded or ragged end thins to a short fork; its spurs go, so that the end is the
    // piece's own (the partition drops them as well).
    removeSpurs(skeleton, cv::Point(-1, -1), params.minLeafBranch_px);
    cv::Mat1f halfWidth;
    cv::distanceTransform(local, halfWidth, cv::DIST_L2, cv::DIST_MASK_5);
    const cv::Mat1w depth = depth_mm(region);

    std::vector<SkeletonEnd> ends;
    // Each tip of the skeleton's graph, its direction read back along its edge.
    const SkeletonGraph graph = skeletonGraph(skeleton, cv::Point(-1, -1));
    for (const SkeletonNode& node : graph.nodes) {
        if (!node.tip || node.ends.size() != 1) continue;
        const SkeletonEdge& edge = graph.edges[static_cast<std::size_t>(node.ends.front() / 2)];
        const bool fromFront = node.ends.front() % 2 == 0;
        const int reach = std::min<int>(kDirectionReach_px, static_cast<int>(edge.pixels.size()));
        if (reach < kMinDirectionReach_px) continue;
        const cv::Point p = node.pixels.front();
        const cv::Point back =
            fromFront ? edge.pixels[static_cast<std::size_t>(reach - 1)]
                      : edge.pixels[edge.pixels.size() - static_cast<std::size_t>(reach)];
        const float z_m = depthNear(depth, local, p);
        if (z_m <= 0.f) continue;
        SkeletonEnd e;
        e.at = p;
        e.out = cv::Point2f(p - back) / static_cast<float>(cv::norm(p - back));
        e.piece = pieces(p);
        e.halfWidth_px = halfWidth(back);
        e.position_m = k.backProject(static_cast<float>(p.x + region.x),
                                     static_cast<float>(p.y + region.y), z_m);
        ends.push_back(e);
    }

    // Every pair of ends of different pieces that face each other, near enough in space.
    const float minCos = std::cos(params.crossingMaxBend_deg * std::numbers::pi_v<float> / 180.f);
    std::vector<Bridge> candidates;
    for (std::size_t i = 0; i < ends.size(); ++i)
        for (std::size_t j = i + 1; j < ends.size(); ++j) {
            const SkeletonEnd &a = ends[i], &b = ends[j];
            if (a.piece == b.piece) continue;
            const float gap_m = glm::length(a.position_m - b.position_m);
            if (gap_m > params.leafGapBridge_m) continue;
            const cv::Point2f step = b.at - a.at;
            const float length = static_cast<float>(cv::norm(step));
            if (length < 1.f) continue;
            const cv::Point2f along = step / length;
            if (along.dot(a.out) < minCos || -along.dot(b.out) < minCos) continue;
            candidates.push_back({static_cast<int>(i), static_cast<int>(j), gap_m});
        }
    // The shortest first; each end and each pair of pieces joined once (no loops).
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Bridge& x, const Bridge& y) { return x.gap_m < y.gap_m; });
    std::vector<int> parent(static_cast<std::size_t>(count));
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<char> used(ends.size(), 0);
    int bridged = 0;
    for (const Bridge& c : candidates) {
        const SkeletonEnd &a = ends[static_cast<std::size_t>(c.a)],
                          &b = ends[static_cast<std::size_t>(c.b)];
        if (used[static_cast<std::size_t>(c.a)] || used[static_cast<std::size_t>(c.b)]) continue;
        const int sa = findSet(parent, a.piece), sb = findSet(parent, b.piece);
        if (sa == sb) continue;
        parent[static_cast<std::size_t>(sa)] = sb;
        used[static_cast<std::size_t>(c.a)] = used[static_cast<std::size_t>(c.b)] = 1;
        const int width_px = std::max(
            1, static_cast<int>(std::lround(2.f * std::min(a.halfWidth_px, b.halfWidth_px))));
        cv::line(mask, a.at + region.tl(), b.at + region.tl(), 255, width_px, cv::LINE_8);
        ++bridged;
    }
    if (bridged > 0)
        report.notes.push_back("joined " + std::to_string(bridged) +
                               " gap(s) where a leaf's piece ends facing another's within " +
                               std::to_string(static_cast<int>(params.leafGapBridge_m * 100.f)) +
                               " cm: one leaf the sensor did not read along a stretch");
    return bridged;
}

}  // namespace meadow::capture::segmentation
