#pragma once
// Internal: one function per segmentation stage (one .cpp each). Masks are CV_8U, 255 = kept.
// Each stage appends what it dropped to the StageReport it is given.
#include <algorithm>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <span>
#include <vector>

#include "meadow/capture/depth_frame.h"
#include "meadow/capture/segmenter.h"

namespace meadow::capture::segmentation {

inline constexpr float kMillimetresPerMetre = 1000.0f;

// The element at size / 2 once sorted (the median of an odd count), reordering `values`.
template <typename T>
T middleOf(std::span<T> values) {
    const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

// `rect` grown by `by_px` on every side, clipped to `within`: the part of an image a filter of
// that reach can read or write around `rect`.
inline cv::Rect grownWithin(const cv::Rect& rect, int by_px, const cv::Rect& within) {
    return cv::Rect(rect.x - by_px, rect.y - by_px, rect.width + 2 * by_px,
                    rect.height + 2 * by_px) &
           within;
}

// temporal_fusion.cpp: per-pixel median of the non-zero readings (of an even count, the nearer or
// the farther middle one in a checkerboard); pixels valid in fewer than minValidFrameFraction of
// the frames read 0. With FusionMethod::NearestRecurring, the nearest recurring reading
// (recurring_readings.h) replaces the median wherever one recurs.
cv::Mat1w fuseFrames(std::span<const DepthFrame> frames, const SegmenterParams& params,
                     StageReport& report);

// depth_band_mask.cpp
struct DepthBand {
    float near_m = 0.0f;
    float far_m = 0.0f;
    bool found = false;
    // Pixels at depths that reach across the frame (a wall or the ground seen at an angle),
    // which the automatic band left out of its histogram; the band must not grow into them.
    // Empty when there are none.
    cv::Mat1b scenery;
    // Why no band was found when the nearest mode is not made of leaves (empty otherwise):
    // "at 0.66 m, is 4.3 times as long as it is wide (leaves: over 5)".
    std::string notLeaves;
};
// The nearest histogram mode with enough mass, widened to its valleys (Fan & Sheng 2017,
// Sec. 4.1 use a user-set depth band; this finds one when the user gives none).
// Only pixels set in `mask` count (ground removed first, so the ground's own mode cannot win).
// A mode whose points form a flat, level patch (ground the plane fit left, or all the ground
// when no plane is fitted) is skipped: a tuft stands up from the ground. When the nearest mode
// left is not made of leaves (unlikeLeaves: a door's edge, a chair), there is no band. When every
// mode is skipped and `groundRemoved` (the plane fit found the ground), the modes are looked for
// again without the depth bins whose pixels alone reach across most of the image columns (a wall
// behind the tuft); the band's `scenery` then holds those bins' pixels.
DepthBand automaticDepthBand(const cv::Mat1w& depth_mm, const cv::Mat1b& mask,
                             const Intrinsics& intrinsics, const SegmenterParams& params,
                             bool groundRemoved, StageReport& report);
// The frame's pixels within the band (the caller leaves out what its mask and `scenery` do).
cv::Mat1b depthBandMask(const cv::Mat1w& depth_mm, DepthBand band, StageReport& report);
// Grows `band` into pixels of `allowed` that are depth-continuous (step <= step_m between
// 8-neighbours) with it and within maxBandHalfWidth_m of the band.
void growDepthContinuous(const cv::Mat1w& depth_mm, const cv::Mat1b& allowed, DepthBand band,
                         const SegmenterParams& params, cv::Mat1b& bandMask, StageReport& report);

// plant_finding.cpp (PCL): PlantFinding::Clusters. The room's large planes removed, the rest
// split into Euclidean clusters, the plant the thin-parted one nearest the image's centre, its
// pot removed.
struct FoundPlant {
    bool found = false;
    cv::Mat1b mask;        // the plant's pixels, pot removed
    cv::Mat1b candidates;  // readings tip trails may follow: the plant's depths, no plane, no
                           // other cluster, no pot
    float near_m = 0.f, far_m = 0.f;
    cv::Point2f base_px;  // where it stands: the top middle of its pot, else its lowest row's
    std::optional<cv::Rect> pot_px;      // the box of the pot it stands in, if it does
    std::string whyNot;                  // "no plant in view: ..." when not found
    std::vector<LeftOutObject> leftOut;  // the largest objects not taken, and why
};
FoundPlant findPlant(const cv::Mat1w& depth_mm, const Intrinsics& intrinsics,
                     const SegmenterParams& params, StageReport& report);

// part_shape.cpp: the shape of the parts of `mask`. `width_m`: the median over its pixels of
// twice the distance to its edge (about half a strip's width), in metres at `depth_m`;
// `elongation`: how many times longer than wide its pieces are, each by its area over that
// width, weighted by its area.
struct PartShape {
    float width_m = 0.f;
    float elongation = 0.f;
};
// Leaves are many times longer than wide (a maize leaf 10-20 times, a grass blade 30 or more);
// a cushion, an arm, a chair's back or a lettuce head is not.
inline constexpr float kMinLeafElongation = 5.f;
// Parts up to this share wider than SegmenterParams::plantMaxMeanWidth_m are a broad-leaved
// plant's when at least kBroadLeafMinElongation times as long as wide (a grown maize shoot:
// 22-115 on the plant bench; a table on legs about 9, a board or a box 3-5).
inline constexpr float kBroadLeafWidthShare = 1.5f;
inline constexpr float kBroadLeafMinElongation = 20.f;
// `fillHoles`: holes up to 3 cm across are filled first (a depth slice of a solid object is
// riddled with them; the clusters of PlantFinding::Clusters are grown back over them).
// `cutFrom`: the object `mask` was cut from (its base taken off), in which the distances to the
// edge are measured, so that the cut is no edge; empty: `mask` itself.
PartShape partShape(const cv::Mat1b& mask, float depth_m, const Intrinsics& intrinsics,
                    bool fillHoles, const cv::Mat1b& cutFrom = {});
// The thick part `mask` stands in at its bottom (a pot and its soil, seen at `depth_m`): what an
// opening by a disc 3.5 cm across keeps that holds its lowest rows, from its bottom up to 1.3
// times its width there, and a rim of 2 px. Frame-sized; empty where there is none.
cv::Mat1b thickBase(const cv::Mat1b& mask, float depth_m, const Intrinsics& intrinsics);
// How parts of `shape` differ from leaves ("made of parts 7.3 cm wide (leaves: under 4 cm, or
// 6 cm when 20 times as long)"), or empty when they are at most
// SegmenterParams::plantMaxMeanWidth_m thick (kBroadLeafWidthShare times that when
// kBroadLeafMinElongation times as long) and, by area, at least kMinLeafElongation times longer
// than wide.
std::string unlikeLeafParts(const PartShape& shape, const SegmenterParams& params);
// How `mask`, its thick base (thickBase) taken off, differs from a plant's leaves: "thick
// throughout" when under a tenth of it is left, else unlikeLeafParts at its median depth; empty
// when it looks like leaves.
std::string unlikeLeaves(const cv::Mat1b& mask, const cv::Mat1w& depth_mm,
                         const Intrinsics& intrinsics, const SegmenterParams& params);

// plane_removal.cpp (PCL). Clears mask pixels on large oblique planes (ground, table top).
// Returns the ground: the plane with the most inliers, as Segmentation::groundPlane.
std::optional<cv::Vec4f> removePlanes(const cv::Mat1w& depth_mm, const Intrinsics& intrinsics,
                                      const SegmenterParams& params, cv::Mat1b& mask,
                                      StageReport& report);

// outlier_removal.cpp (PCL for Statistical).
void removeOutliers(const cv::Mat1w& depth_mm, const Intrinsics& intrinsics,
                    const SegmenterParams& params, cv::Mat1b& mask, StageReport& report);

// morphology_cleanup.cpp: closing, optional opening, edge smoothing, small regions dropped,
// small holes filled, thin fragments linked (fragment_links.cpp).
void cleanUpMask(const SegmenterParams& params, cv::Mat1b& mask, StageReport& report);
// fragment_links.cpp: small elongated parts of the mask (a thin blade the sensor broke) joined
// to another part lying past one of their ends, along their axis, within fragmentLinkGap_px.
// `labels` and `stats`: the mask's 8-connected parts (cv::connectedComponentsWithStats), with
// `dropped` ones (by label) no longer in it.
void linkFragments(const SegmenterParams& params, const cv::Mat1i& labels, const cv::Mat& stats,
                   const std::vector<char>& dropped, cv::Mat1b& mask, StageReport& report);
// leaf_gaps.cpp: ends of the mask's skeleton in different pieces that face each other within
// SegmenterParams::leafGapBridge_m in space, each running on towards the other within
// crossingMaxBend_deg, are joined by a line of the leaf's width: one leaf the sensor did not read
// along a stretch. Shortest first; each end once, each pair of pieces once. Returns how many.
int bridgeLeafGaps(cv::Mat1b& mask, const cv::Mat1w& depth_mm, const Intrinsics& intrinsics,
                   const SegmenterParams& params, StageReport& report);
// contour_smoothing.cpp: every contour of the mask averaged along its length (Gaussian of
// sigma_px points), no point moved more than maxShift_px, tips and valleys kept, and the mask
// redrawn from them. 0 for either = off.
void smoothContours(cv::Mat1b& mask, float sigma_px, float maxShift_px, StageReport& report);
// The part of the frame the clean-up and everything after it can touch: the mask's bounding
// box grown by the farthest any clean-up filter reaches, and one pixel more so that a hole
// touches the region's border only if it is open to the frame's background. Clean-up inside it
// gives the same pixels as over the whole frame. Empty for an empty mask.
cv::Rect cleanUpRegion(const cv::Mat1b& mask, const SegmenterParams& params);

// tip_trails.cpp: dotted lines of in-band readings (`candidates`, before outlier removal and
// clean-up) that run on from the mask, as a blade's tip does under lateral noise, are linked
// back onto `mask` one pixel wide. Returns what was added: a mask over `box` of the frame
// (both empty if nothing was).
struct TipTrails {
    cv::Rect box;
    cv::Mat1b added;
    // Share of the pixels 2-3 px outside the mask that hold in-band readings: how ragged the
    // sensor left the edges (Segmentation::edgeRaggedness). 0 when not measured.
    float raggedness = 0.f;
    [[nodiscard]] bool holds(cv::Point frame_px) const {
        return box.contains(frame_px) && added(frame_px - box.tl()) != 0;
    }
};
// `recurring` (may be empty): in-band readings that recur over a longer run of frames
// (recurring_readings.h); trails may run through them, but how ragged the edges are is measured
// on `candidates` alone, this frame's own readings.
TipTrails recoverTipTrails(const cv::Mat1b& candidates, const cv::Mat1b& recurring,
                           const SegmenterParams& params, cv::Mat1b& mask, StageReport& report);

// sensed_extent.cpp: per row and column, the first and last pixel with a reading, where the
// sensor's band of no readings along an image border (at most a tenth of the frame) ends.
struct SensedExtent {
    std::vector<int> firstX, lastX;             // per row
    std::vector<int> firstY, lastY;             // per column
    static SensedExtent whole(cv::Size frame);  // every pixel sensed (a mask, no depth)
    static SensedExtent of(const cv::Mat1w& depth_mm);
    // Whether p lies within a pixel of the image border or of such a band.
    [[nodiscard]] bool atEdge(cv::Point p) const;
    // Whether p lies within a pixel of the bottom border or of the band along it: a cluster
    // reaching it may have its base below what was sensed.
    [[nodiscard]] bool atBottom(cv::Point p) const;
};

// contour_extraction.cpp: one cluster per remaining region, with contour, centre, base point
// and reference; flags holes (crossing blades) and hidden bases (a cluster reaching the bottom
// of what was sensed, SensedExtent::atBottom).
// Only `region` of the frame-sized mask is searched (cleanUpRegion: nothing lies outside it).
std::vector<BladeCluster> extractClusters(const cv::Mat1b& mask, const cv::Rect& region,
                                          const SensedExtent& sensed, const SegmenterParams& params,
                                          StageReport& report);
// The cluster's own pixels: inside its contour and on `mask` (frame-sized), over the contour's
// bounding box, which `box` receives; the region the partitions cut.
cv::Mat1b clusterRegion(const BladeCluster& cluster, const cv::Mat1b& mask, cv::Rect& box);

// blade_partition.cpp: persistent minima of the smoothed distance cut each cluster's contour
// into blades ordered base A -> tip -> base B, each with its mask. `depth_mm`: the frame's
// readings (empty for a given mask) and `raggedness` (Segmentation::edgeRaggedness) decide
// whether the fork zone is re-decided by depth (SegmenterParams::forkByDepth).
std::vector<BladeContour> partitionCluster(BladeCluster& cluster, const cv::Mat1b& mask,
                                           const cv::Mat1w& depth_mm, float raggedness,
                                           const SegmenterParams& params, int firstId,
                                           StageReport& report);
// crossing_flags.cpp: flags overlapping the blades the contour partition cut at a crossing (the
// cluster's skeleton runs straight on through one junction along two strands).
void flagCutCrossings(std::span<BladeContour> blades, const BladeCluster& cluster,
                      const cv::Mat1b& mask, const cv::Mat1w& depth_mm,
                      const SegmenterParams& params);
// stem_partition.cpp: PartitionMethod::StemGraph. The cluster's skeleton as a graph, its edges
// joined through the junctions by the smoothest continuation in direction and, where `depth_mm`
// holds readings (it may be empty), in depth; the strand from the plant's foot that most others
// end on is the stem, up to the highest node a leaf leaves it at; every other strand is a leaf,
// with the cluster pixels nearest it (both strands' at a crossing). Contours run from the leaf's
// base (where it meets the stem) round its tip and back. Sets the cluster's stemLine_px.
// `plantBase` (when known, from PlantFinding::Clusters): where the plant stands; the stem is
// sought from the skeleton's pixel nearest that point rather than from the cluster's lowest
// point, which on a plant of drooping leaves is a leaf's tip; what lies wholly below it is the
// pot's or the ground's, unless it hangs past `plantPot` (the pot's box, when plant finding took
// one off). `plantStem_px` (frame coordinates, may be empty): the stem another cluster of the
// same plant holds; a cluster without a stem of its own (a leaf cut off from the rest) bases its
// leaves by it.
std::vector<BladeContour> partitionByStem(BladeCluster& cluster, const cv::Mat1b& mask,
                                          const cv::Mat1w& depth_mm, const SegmenterParams& params,
                                          int firstId, const std::optional<cv::Point2f>& plantBase,
                                          const std::optional<cv::Rect>& plantPot,
                                          const std::vector<cv::Point>& plantStem_px,
                                          StageReport& report);
// fork_partition.cpp: the pixels of the fork zone (between each blade's two valleys and the base
// point) re-decided by the blades' centre lines continued to the base and by depth. Box
// coordinates: `owner` (blade index + 1) and `region` cover the cluster's box at `origin` of the
// frame; `depth_mm` is frame-sized. Returns how many pixels changed blade.
int assignForkZone(std::span<const BladeContour> pieces, cv::Point origin, cv::Point2f base_px,
                   const cv::Mat1b& region, const cv::Mat1w& depth_mm, float depthSigma_mm,
                   cv::Mat1i& owner);
// Persistence of every local minimum of a circular signal (sublevel-set filtration); the
// global minimum gets +infinity. Returned as (index, persistence), sorted by index.
std::vector<std::pair<int, float>> circularMinimaPersistence(std::span<const float> signal);
std::vector<float> smoothCircular(std::span<const float> signal, float sigma_samples);

// blade_flags.cpp: per-blade flags with reasons (thin, curled, truncated, overlapping).
// `raggedness`: Segmentation::edgeRaggedness (the interior-share TooThin test needs ragged edges).
// `sensed`: where a contour counts as truncated (SensedExtent::atEdge).
void flagBlades(std::span<BladeContour> blades, const BladeCluster& cluster, cv::Size frameSize,
                const SensedExtent& sensed, const SegmenterParams& params, float raggedness);
void addFlag(BladeContour& blade, BladeFlag flag, std::string reason);
void addFlag(BladeCluster& cluster, BladeFlag flag, std::string reason);

}  // namespace meadow::capture::segmentation
