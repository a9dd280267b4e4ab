#pragma once
// Continuing a segmented blade past its visible tip. A blade's tip thins below the sensor's
// resolution before it ends, so the segmented contour stops short of the true tip. Where the
// measured width tapers toward the tip, the width's linear trend over the upper part of the chain
// is extrapolated to zero, and the skeleton is continued straight along its 3D end tangent by that
// length. The defaults were chosen on the leaf presets at nominal noise. The piece is straight:
// a drooping tip ends beside the true curve (see docs/capture.md#tip-extension).
#include <optional>

#include "meadow/modeling/skeleton.h"

namespace meadow::modeling {

struct TipParams {
    // Continue each segmented blade past its tip (fitSegmentedBlade).
    bool enabled = true;
    // Part of the chain (arc fractions of the visible skeleton) whose widths give the linear
    // trend: from widthFitFrom to widthFitTo. The last (1 - widthFitTo) is left out: the smoothing
    // and the contour's closing pull the widths there to 0 whatever the blade does.
    float widthFitFrom = 0.7f;
    float widthFitTo = 0.95f;
    // fitSegmentedBlade: a blade whose tip the segmenter followed along a tip trail
    // (BladeContour::tipOnTrail) ends in its own taper, one or two pixels wide; its end is then
    // evidence of where the tip is, and the trend runs to the end of the chain (widthFitTo 1).
    bool toEndOnTrail = true;
    // Part of the chain (from tangentFitFrom to the tip) whose points give the end tangent by a
    // least-squares line through them against arc length.
    float tangentFitFrom = 0.87f;
    // Longest extension, as a fraction of the visible skeleton's 3D length: with the segmenter's
    // tip trails less of the tip is missing, and shorter caps overshoot less. And for a blade
    // whose tip lies on a trail (BladeContour::tipOnTrail) the visible end is within a pixel or
    // two of the tip: maxExtensionOnTrail, smaller still but not 0 (trail tips still fall short).
    // Both chosen by tip RMS on the leaf presets at nominal noise (docs/capture.md#tip-extension).
    float maxExtensionFraction = 0.1f;
    float maxExtensionOnTrail = 0.05f;
    // Where the segmenter's trails could also run through readings recurring over a dozen
    // frames (Segmentation::recurringFrames > 0), a trail tip ends where the tip became too thin
    // to be read in enough frames, and what is still unseen of it is the part too narrow for the
    // sensor's pixels: the farther the blade, the longer that part. Every trail tip of such a
    // segmentation is extended by this many pixels over the blade's width in pixels, as a
    // fraction of its visible length (recurringTrailExtension), whatever the widths' trend says
    // (along a trail they are the trail's own 1-2 px, not the blade's taper): the length over
    // which an even taper from the blade's widest to nothing along its whole length narrows by
    // this many pixels. Seen from twice as far, half as many pixels wide, a blade is extended
    // twice as far. A fixed fraction of the length would let near tips overshoot and stop far
    // ones short (see docs/capture.md#tip-extension, docs/measurements/tip_reach.md).
    float extensionOnRecurringTrail_px = 0.2f;
    // When > 0, extendSkeletonTip extends by this fraction of the visible length instead of to
    // the width trend's zero (segmentedBladeSkeleton sets it for recurring trail tips).
    float fixedExtensionFraction = 0.f;
    // The trend's slope must be negative by at least this many standard errors.
    float minSlopeSignificance = 2.f;
};

// Extends the skeleton from its tip (points_m.back()) along the end tangent by the length at which
// the widths' linear trend reaches zero (capped at maxExtensionFraction of the skeleton's length),
// or by fixedExtensionFraction of it when that is set, and resamples every per-point sequence to
// the same number of points by 3D arc length. Widths past widthFitTo follow the trend (where it
// tapers), down to 0 at the new tip. Sets tipExtension_m and tipPoints. Without
// fixedExtensionFraction, leaves the skeleton as it is (tipExtension_m = 0) when the widths do not
// taper (slope >= 0 or not significant) or the trend reaches zero before the tip; always when the
// chain has fewer than 8 points.
void extendSkeletonTip(Skeleton& skeleton, const TipParams& params = {});

// The extension, as a fraction of the visible length, of a trail tip of a segmentation with
// recurring readings: extensionOnRecurringTrail_px over the blade's width in pixels (the 90th
// percentile of skeleton.width_px, so that a few widths the fork or the noise inflate do not set
// it), at most maxExtensionFraction; nullopt when the skeleton has no pixel widths.
[[nodiscard]] std::optional<float> recurringTrailExtension(const Skeleton& skeleton,
                                                           const TipParams& params = {});

}  // namespace meadow::modeling
