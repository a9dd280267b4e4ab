#pragma once
// The plant's stem as capture sees it: how tall it stands in one segmentation, and over a
// capture (the library's `stem`, docs/formats.md#archetype-library).
#include <optional>
#include <vector>

#include "meadow/capture/depth_frame.h"
#include "meadow/capture/segmenter.h"
#include "meadow/modeling/archetype_library.h"

namespace meadow::modeling {

// The straight distance in metres from the stem's foot (where the plant stands) to its top (the
// highest point a leaf leaves it at), both back-projected at the median depth read within 3 px;
// the longest stem when several clusters have one. Empty without a stem
// (BladeCluster::stemLine_px, PartitionMethod::StemGraph) or without readings at its ends.
[[nodiscard]] std::optional<float> stemHeight_m(const capture::Segmentation& segmentation,
                                                const capture::DepthFrame& frame);

// The library's stem from the heights of the segmentations that saw one: their median, and how
// many there were. Empty when none did.
[[nodiscard]] std::optional<StemMeasure> stemOf(std::vector<float> heights_m);

}  // namespace meadow::modeling
