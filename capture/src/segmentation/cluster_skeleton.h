#pragma once
// One cluster's region as a skeleton graph with its strands followed through the junctions: what
// the stem partition cuts leaves from, and where the contour partition's crossing check looks.
#include <optional>

#include "meadow/capture/segmenter.h"
#include "segmentation/skeleton_graph.h"

namespace meadow::capture::segmentation {

struct ClusterSkeleton {
    cv::Rect box;  // the cluster's box in the frame; everything below is in box coordinates
    cv::Mat1b region, skeleton;
    std::vector<cv::Point> onSkeleton;  // the skeleton's pixels, spurs removed
    cv::Point root;                     // the skeleton pixel nearest the foot
    int spurs = 0;                      // spurs under minLeafBranch_px removed
    cv::Mat1f halfWidth;                // distance to the region's edge
    SkeletonGraph graph;                // close junctions merged
    Strands strands;
};

// The region inside the cluster's contour and `mask`, thinned; its spurs removed, rooted at the
// skeleton pixel nearest `foot_px` (frame coordinates); its strands joined through the junctions
// by direction and, where `depth_mm` (frame-sized, may be empty) reads, depth. Empty when the
// region thins to nothing.
std::optional<ClusterSkeleton> clusterSkeleton(const BladeCluster& cluster, const cv::Mat1b& mask,
                                               const cv::Mat1w& depth_mm,
                                               const SegmenterParams& params, cv::Point2f foot_px);

// The junctions two or more strands run through: crossings followed through.
std::vector<int> crossingNodes(const SkeletonGraph& graph, const Strands& strands);

}  // namespace meadow::capture::segmentation
