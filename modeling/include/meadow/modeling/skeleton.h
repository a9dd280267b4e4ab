#pragma once
// Skeleton and expansion width of one blade by symmetric contour matching (Fan & Sheng 2017,
// Sec. 4.3): the two sides of the blade contour (base A -> tip and base B -> tip) are resampled
// by arc length; the i-th points of both sides are matched, their midpoint is the i-th skeleton
// point and their distance the expansion width. The skeleton is then lifted to camera space
// (metres) with the frame's depth and intrinsics.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "meadow/capture/blade_contour.h"
#include "meadow/capture/depth_frame.h"

namespace meadow::modeling {

struct SkeletonParams {
    // Matched pairs (= skeleton points, base and tip included). 128 is the paper's full knot
    // count before refining (their Fig. 12).
    int points = 128;
    // Half size of the depth window around a skeleton point (2 -> 5 x 5 pixels). Small: a blade
    // is only a few pixels wide at 1 m, and the window must stay inside it.
    int depthWindowRadius_px = 2;
    // Passes of the [1 2 1] / 4 smoothing kernel over the widths (after a 3-tap median that
    // removes single-pixel spikes of the integer contour).
    int widthSmoothingPasses = 4;
    // Longer side / shorter side above which the symmetric match is not trusted.
    float maxSideLengthRatio = 1.35f;
    // Mean |DT(midline) - width / 2| / (width / 2) above which the midline is taken to be off the
    // distance-transform ridge (the blade is asymmetric or curls).
    float maxRidgeOffsetFraction = 0.35f;
    // A depth differing from the running median along the chain by more than this is a flying
    // pixel or a hole edge: it is dropped and filled from its neighbours along the chain.
    float maxDepthJump_m = 0.015f;
    // Readings outside [minDepth_m, maxDepth_m] are not the blade's (0 = no bound on that side).
    // fitSegmentedBlade sets them to the tuft's depth range (Segmentation::tuftNearest_m and
    // tuftFarthest_m): mask pixels the clean-up or a tip trail filled in can read the wall.
    float minDepth_m = 0.0f;
    float maxDepth_m = 0.0f;
};

struct Skeleton {
    std::vector<glm::vec2> midline_px;  // base -> tip, image pixels (sub-pixel)
    std::vector<glm::vec2> across_px;   // unit direction side A -> side B at each point
    std::vector<float> width_px;        // smoothed expansion width, pixels
    std::vector<glm::vec3> points_m;    // base -> tip, camera space, metres
    std::vector<float> width_m;         // smoothed expansion width, metres
    std::vector<float> arcFraction;     // arc length from the base / total, along points_m
    std::vector<float> depth_m;         // depth used for each point (after hole filling)
    int filledDepths = 0;               // points whose depth came from neighbours on the chain
    // Camera-space step of one pixel across the blade (side A -> side B) at each point: its
    // lateral metres and the depth change over it, read as a line through the depths of the
    // blade's pixels across its width there. It tells how the face tilts about the spine
    // (blade_fit.h, fitTwist). Zero where the blade is too narrow or too sparsely read to tell.
    std::vector<glm::vec3> acrossStep_m;
    // Symmetry diagnostics.
    float sideLengthRatio = 1.f;      // longer / shorter contour side
    float ridgeOffsetFraction = 0.f;  // see SkeletonParams::maxRidgeOffsetFraction
    bool asymmetric = false;
    // Rooting at the tuft's base (blade_root.h): the straight piece added below the segmented
    // base (0: not rooted), how many leading points lie on it (no contour behind them), and
    // whether rooting was asked for but refused (the reason is in `reasons`).
    float baseExtension_m = 0.f;
    int rootPoints = 0;
    bool baseNotRooted = false;
    // Tip extension (blade_tip.h): the straight piece added past the visible tip (0: none) and
    // how many trailing points lie on it (no contour behind them).
    float tipExtension_m = 0.f;
    int tipPoints = 0;
    std::vector<std::string> reasons;  // one line per raised concern
};

// Points of an open polyline resampled to n points evenly spaced by arc length, first and last
// kept. Requires n >= 2 and a non-empty polyline.
std::vector<glm::vec2> resampleByArcLength(const std::vector<glm::vec2>& polyline, int n);
std::vector<glm::vec3> resampleByArcLength(const std::vector<glm::vec3>& polyline, int n);

// The 2D part: sides, symmetric matching, smoothed widths, symmetry diagnostics (no depth).
// Fills midline_px, across_px, width_px, sideLengthRatio, ridgeOffsetFraction, asymmetric,
// reasons. Requires a contour with at least 3 points and 0 < tipIndex < size - 1.
Skeleton matchSymmetricContour(const capture::BladeContour& blade,
                               const SkeletonParams& params = {});

// Full skeleton: matchSymmetricContour, then depth and back-projection. Throws ModelingError when
// the blade has no valid depth reading at all.
Skeleton extractSkeleton(const capture::BladeContour& blade, const capture::DepthFrame& frame,
                         const SkeletonParams& params = {});

// Independent width check (width_check.cpp): twice the Euclidean distance transform (DT) of the
// blade mask, sampled bilinearly at each midline point, in pixels; comparable with
// Skeleton::width_px (boundary distance + 1 pixel) within about half a pixel (see the file).
// The mask's pixel (0, 0) is frame pixel maskOrigin_px (capture::BladeContour::maskOrigin_px);
// midline points are in frame pixels.
std::vector<float> distanceTransformWidth_px(const cv::Mat1b& mask,
                                             const std::vector<glm::vec2>& midline_px,
                                             cv::Point maskOrigin_px = {0, 0});

// Smoothing of a width sequence: 3-tap median, then `passes` of [1 2 1] / 4; ends kept in place.
std::vector<float> smoothWidths(const std::vector<float>& width, int passes);

}  // namespace meadow::modeling
