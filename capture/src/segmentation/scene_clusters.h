#pragma once
// The scene's objects: what the plane removal leaves, split into Euclidean clusters (PCL) on a
// sampling grid and grown back to every reading beside them, measured for plant_finding.cpp.
#include <opencv2/core.hpp>
#include <vector>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation::scene {

// One object of the scene. euclideanClusters measures its pixels, bounds, depth and height;
// plant finding adds its parts' width, its share near the planes and its pot.
struct Cluster {
    cv::Mat1b mask;  // frame-sized
    int area_px = 0;
    cv::Point2f centroid_px;
    float medianDepth_m = 0.f;
    float meanWidth_m = 0.f;
    float height_m = 0.f;
    float nearPlanes = 0.f;  // share of its pixels near a removed plane (plant_finding.cpp)
    cv::Mat1b pot;           // the thick part at its bottom, removed from mask
    cv::Vec3f lo{1e9f, 1e9f, 1e9f}, hi{-1e9f, -1e9f, -1e9f};  // camera-space bounds of its samples
};

// Whether the two clusters' camera-space bounds come within `margin_m` of each other on every axis.
inline bool boundsMeet(const Cluster& a, const Cluster& b, float margin_m) {
    for (int i = 0; i < 3; ++i)
        if (a.lo[i] - margin_m > b.hi[i] || b.lo[i] - margin_m > a.hi[i]) return false;
    return true;
}

// Euclidean clusters of `rest` on a stride, each grown back to every pixel of `rest` beside its
// samples at a depth within the tolerance (SegmenterParams::clusterTolerance_m, grown with depth
// as planeTolerance_m). Depth jumps (a sensor's mixed readings between a leaf and what lies
// behind it) part clusters.
std::vector<Cluster> euclideanClusters(const cv::Mat1w& depth_mm, const Intrinsics& k,
                                       const SegmenterParams& p, const cv::Mat1b& rest);

}  // namespace meadow::capture::segmentation::scene
