#pragma once
// Rooting a segmented blade at its tuft's base. The segmenter partitions a tuft's contour at the
// minima of its distance to the cluster's base point (capture/segmenter.h), so every blade's
// contour starts where it forks from its neighbours, and the shared trunk below the fork belongs
// to no single blade: the segmented blade starts well above its root. The blades
// of a tuft grow from one base, so the skeleton is continued from its lower end straight down to
// the cluster's base point in 3D, and the fitted v0 is the tuft's root.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>

#include "meadow/capture/depth_frame.h"
#include "meadow/capture/segmenter.h"
#include "meadow/modeling/skeleton.h"

namespace meadow::modeling {

struct RootParams {
    // Continue each blade to its cluster's base point (fitSegmentedBlade). Off: the spine starts
    // where the segmented contour starts, at the fork.
    bool enabled = true;
    // Half size of the window around the base point whose valid depth readings (inside the
    // cluster mask) give the base's depth by their median; grown one pixel at a time up to
    // maxDepthWindowRadius_px while fewer than minDepthReadings are found.
    int depthWindowRadius_px = 3;
    int maxDepthWindowRadius_px = 12;
    int minDepthReadings = 5;
    // A base farther from the blade's lower end than this multiple of the segmented skeleton's
    // length is not the blade's root (a blade not attached to the tuft, a wrong cluster): the
    // blade is left unrooted and flagged. A true root piece stays well within it.
    float maxExtensionFraction = 1.f;
    // The base point is the centroid of the cluster's lowest rows, and the plane removal clears
    // what lies within its tolerance of the ground, so the lowest visible part of a tuft sits a
    // few millimetres above its root (see docs/capture.md#rooting).
    // toLowestRow: the base moves down to the cluster's lowest pixel under it. dropToGround:
    // then, with a ground plane from the segmentation at most maxGroundDrop_m below, it moves
    // onto that plane along its normal: a tuft grows from the ground.
    bool toLowestRow = true;
    bool dropToGround = true;
    float maxGroundDrop_m = 0.04f;
};

struct ClusterBase {
    glm::vec2 base_px{0.f};  // BladeCluster::basePoint_px, on the lowest row with toLowestRow
    float depth_m = 0.f;     // median of the cluster's valid readings near it
    glm::vec3 base_m{0.f};   // back-projected, camera space; on the ground when dropped
    int depthReadings = 0;
    float groundDrop_m = 0.f;  // how far base_m was moved down onto the ground plane
};

// Whether the blade is a leaf cut where it leaves its cluster's stem (BladeCluster::stemLine_px,
// PartitionMethod::StemGraph): such a leaf is not rooted at the cluster's base.
[[nodiscard]] bool leavesAStem(const capture::Segmentation& segmentation, int bladeId);

// The base of the cluster whose bladeIds hold `bladeId`: its base point, with the median depth of
// the valid readings inside Segmentation::clusterMask (all readings when it is empty) near it.
// Empty when no cluster lists the blade or no valid reading lies within maxDepthWindowRadius_px.
std::optional<ClusterBase> clusterBase(const capture::Segmentation& segmentation, int bladeId,
                                       const capture::DepthFrame& frame,
                                       const RootParams& params = {});

// Continues the skeleton from its base end (points_m.front()) straight to base.base_m and
// resamples every per-point sequence to the same number of points by 3D arc length; the new
// points carry the width of the blade's lowest part. Sets baseExtension_m and rootPoints.
// Refuses, leaving the skeleton's points as they are, when the base is farther than
// params.maxExtensionFraction x the skeleton's length or lies on the blade's side of its lower
// end (above it along the blade): then sets baseNotRooted and adds a reason.
void rootSkeleton(Skeleton& skeleton, const ClusterBase& base, const RootParams& params = {});

}  // namespace meadow::modeling
