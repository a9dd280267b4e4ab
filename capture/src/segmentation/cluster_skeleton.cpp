#include "segmentation/cluster_skeleton.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

std::optional<ClusterSkeleton> clusterSkeleton(const BladeCluster& cluster, const cv::Mat1b& mask,
                                               const cv::Mat1w& depth_mm,
                                               const SegmenterParams& params, cv::Point2f foot_px) {
    if (cluster.contour_px.empty()) return std::nullopt;
    ClusterSkeleton c;
    c.region = clusterRegion(cluster, mask, c.box);
    cv::ximgproc::thinning(c.region, c.skeleton, cv::ximgproc::THINNING_ZHANGSUEN);
    cv::findNonZero(c.skeleton, c.onSkeleton);
    if (c.onSkeleton.empty()) return std::nullopt;
    const cv::Point2f foot = foot_px - cv::Point2f(c.box.tl());
    c.root = *std::min_element(
        c.onSkeleton.begin(), c.onSkeleton.end(), [&](const cv::Point& a, const cv::Point& b) {
            return cv::norm(cv::Point2f(a) - foot) < cv::norm(cv::Point2f(b) - foot);
        });
    // Spurs of the skeleton (a bump in the edge) are not leaves.
    c.spurs = removeSpurs(c.skeleton, c.root, params.minLeafBranch_px);
    cv::findNonZero(c.skeleton, c.onSkeleton);
    cv::distanceTransform(c.region, c.halfWidth, cv::DIST_L2, cv::DIST_MASK_5);
    c.graph = skeletonGraph(c.skeleton, c.root);
    mergeCloseJunctions(c.graph, c.halfWidth);
    const cv::Mat1w depth = depth_mm.empty() ? cv::Mat1w() : cv::Mat1w(depth_mm(c.box));
    c.strands = followStrands(c.graph, c.halfWidth, depth,
                              {params.crossingMaxBend_deg, params.crossingDepthStep_mm});
    return c;
}

std::vector<int> crossingNodes(const SkeletonGraph& graph, const Strands& strands) {
    std::vector<int> through(graph.nodes.size(), 0);
    for (const Strand& s : strands.strands)
        for (const int n : s.through) ++through[static_cast<std::size_t>(n)];
    std::vector<int> out;
    for (std::size_t n = 0; n < through.size(); ++n)
        if (through[n] >= 2) out.push_back(static_cast<int>(n));
    return out;
}

}  // namespace meadow::capture::segmentation
