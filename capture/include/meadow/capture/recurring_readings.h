#pragma once
// Readings that recur over the frames of a still tuft, for the segmenter's tip trails.
//
// A blade's thin tip is a dotted line in every frame: lateral noise hands most of its pixels to
// the wall behind, and a different half in each frame. The per-pixel median of a fused group
// keeps the wall there, so the tip trails of a group see only the dots that one group left. Over
// a dozen frames most pixels of the tip are read as blade a few times, always at the blade's
// depth, while speckle beside an edge is read as blade once in a while at scattered depths
// (see docs/capture.md#readings-that-recur-over-a-run, docs/measurements/tip_reach.md).
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <span>
#include <string>

#include "meadow/capture/depth_frame.h"

namespace meadow::capture {

struct RecurringParams {
    // A pixel recurs when at least this share of the frames, and at least minFrames of them,
    // read it within agreement_mm of one another.
    float minShare = 0.25f;
    int minFrames = 3;
    int agreement_mm = 10;
    // Empty when usable; otherwise what is wrong.
    [[nodiscard]] std::string problem() const;
};

struct RecurringReadings {
    // Per pixel, the middle of the nearest group of agreeing readings (0: none recurs).
    cv::Mat1w depth_mm;
    int frames = 0;           // frames it was taken over
    int neededFrames = 0;     // readings a pixel needed
    int recurringPixels = 0;  // pixels with a recurring reading
};

// Throws CaptureError for no frames, frames of different sizes, or unusable params.
[[nodiscard]] RecurringReadings recurringReadings(std::span<const DepthFrame> frames,
                                                  const RecurringParams& params = {});

}  // namespace meadow::capture
