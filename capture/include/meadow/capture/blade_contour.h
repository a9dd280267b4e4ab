#pragma once
// What capture hands to modeling: one ordered contour per blade, from one side of the base,
// over the tip, to the other side of the base (Fan & Sheng 2017, Sec. 4.2).
#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

#include "meadow/capture/depth_frame.h"
#include "meadow/core/enum_names.h"

namespace meadow::capture {

// Why a blade or cluster cannot be trusted; empty flags mean none was raised.
enum class BladeFlag {
    Overlapping,    // crosses or touches another blade: the cut may be wrong
    CurlsSideways,  // the contour folds back on itself along the blade
    TooThin,        // narrower than the sensor resolves (< ~2 px)
    BaseHidden,     // the base is not visible (camera pose, occlusion)
    Asymmetric,     // the two sides differ more than the symmetric match tolerates
    Truncated,      // touches the image border
};
inline constexpr EnumNames<BladeFlag, 6> kBladeFlagNames{{{
    {BladeFlag::Overlapping, "overlapping"},
    {BladeFlag::CurlsSideways, "curls-sideways"},
    {BladeFlag::TooThin, "too-thin"},
    {BladeFlag::BaseHidden, "base-hidden"},
    {BladeFlag::Asymmetric, "asymmetric"},
    {BladeFlag::Truncated, "truncated"},
}}};
inline std::string toString(BladeFlag flag) { return std::string(kBladeFlagNames.name(flag)); }

struct BladeContour {
    int id = 0;                         // 1.. within its frame
    std::vector<cv::Point> contour_px;  // base side A -> tip -> base side B, closed implicitly
    int tipIndex = 0;                   // index of the tip point in contour_px
    // The blade's pixels (255), over the blade's bounding box only: a frame holds a dozen
    // blades, and frame-sized masks cost more to fill and to scan than the segmentation itself.
    // mask(y, x) is frame pixel maskOrigin_px + (x, y). A frame-sized mask has origin (0, 0).
    cv::Mat1b mask;
    cv::Point maskOrigin_px{0, 0};
    std::vector<BladeFlag> flags;
    std::vector<std::string> reasons;  // one human-readable line per flag
    // The tip lies on a tip trail: dotted readings past the cleaned mask that the segmenter
    // linked back (SegmenterParams::tipTrailMinReach_px). The contour then ends where the
    // readings do, in the tip's own taper, not where a too-thin tip was cut off.
    bool tipOnTrail = false;

    // Whether frame pixel p_px belongs to the blade.
    [[nodiscard]] bool covers(cv::Point p_px) const;
    // The mask placed in a frame of frameSize (0 elsewhere), to compare with frame-sized images.
    [[nodiscard]] cv::Mat1b frameMask(cv::Size frameSize) const;
    // The part of the frame the mask covers.
    [[nodiscard]] cv::Rect maskBox_px() const { return {maskOrigin_px, mask.size()}; }
};

// The index of the point of `outline` nearest `p` (the first of equals; 0 for an empty outline):
// where a blade's contour starts (nearest its base) and where its tip is.
[[nodiscard]] int nearestPointIndex(const std::vector<cv::Point>& outline, cv::Point2f p);

}  // namespace meadow::capture
