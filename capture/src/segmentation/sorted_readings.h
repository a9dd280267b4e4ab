#pragma once
// A still tuft's frames sorted per pixel, nearest reading first, for the per-pixel statistics of
// temporal fusion (temporal_fusion.cpp) and recurring readings (recurring_readings.cpp).
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <span>
#include <vector>

#include "meadow/capture/depth_frame.h"

namespace meadow::capture::segmentation {

// Stands for "no reading" in the sorted images: farther than any depth a uint16 millimetre frame
// holds but this one, which no sensor reports.
inline constexpr std::uint16_t kNoReading = 0xffff;

// How many of `frames` frames a share of them is, rounded up, and at least `atLeast`.
[[nodiscard]] int framesForShare(float share, std::size_t frames, int atLeast);

// sorted[k](y, x) is the (k+1)-th nearest reading of pixel (y, x) over the frames, kNoReading
// after its last one. Frames must share one size (unchecked). By a sorting network over whole
// images (Batcher's odd-even merge sort, each comparator an element-wise min and max): a
// per-pixel sort costs several times as much.
[[nodiscard]] std::vector<cv::Mat1w> sortedReadings(std::span<const DepthFrame> frames);

// The nearest run of `needed` sorted readings that agree within agreement_mm, per pixel: its
// middle reading, 0 where none does (recurring_readings.h). `sorted` as sortedReadings gives it.
[[nodiscard]] cv::Mat1w nearestRecurring(const std::vector<cv::Mat1w>& sorted, int needed,
                                         int agreement_mm);

}  // namespace meadow::capture::segmentation
