// Crossings the contour partition cut through. Fan & Sheng's partition assumes blades fanning
// apart from one base: two blades crossing in an X are cut at the crossing into four pieces that
// each look like a plain blade. The cluster's skeleton tells: there it runs straight on through
// one junction along two strands (the stem partition follows them through, stem_partition.cpp).
#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <string>

#include "segmentation/cluster_skeleton.h"
#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

void flagCutCrossings(std::span<BladeContour> blades, const BladeCluster& cluster,
                      const cv::Mat1b& mask, const cv::Mat1w& depth_mm,
                      const SegmenterParams& params) {
    if (blades.size() < 2) return;
    const std::optional<ClusterSkeleton> sk =
        clusterSkeleton(cluster, mask, depth_mm, params, cluster.basePoint_px);
    if (!sk) return;
    for (const int n : crossingNodes(sk->graph, sk->strands)) {
        const SkeletonNode& node = sk->graph.nodes[static_cast<std::size_t>(n)];
        // The crossing reaches as far as the mask is wide there, beyond the junction's pixels.
        cv::Mat1b crossing(sk->box.size(), std::uint8_t{0});
        float halfWidth_px = 0.f;
        for (const cv::Point& p : node.pixels) {
            crossing(p) = 255;
            halfWidth_px = std::max(halfWidth_px, sk->halfWidth(p));
        }
        const int reach_px = 2 * static_cast<int>(halfWidth_px) + 3;
        cv::dilate(crossing, crossing,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, {reach_px, reach_px}));
        const cv::Point at = cv::Point(node.centre) + sk->box.tl();
        for (BladeContour& b : blades) {
            const cv::Rect common = b.maskBox_px() & sk->box;
            if (common.empty() || cv::countNonZero(b.mask(common - b.maskOrigin_px) &
                                                   crossing(common - sk->box.tl())) == 0)
                continue;
            addFlag(b, BladeFlag::Overlapping,
                    "it crosses another blade at (" + std::to_string(at.x) + ", " +
                        std::to_string(at.y) +
                        "), where the mask's skeleton runs straight on along both: the contour "
                        "partition cut them into pieces there (--partition stem-graph follows "
                        "crossings)");
        }
    }
}

}  // namespace meadow::capture::segmentation
