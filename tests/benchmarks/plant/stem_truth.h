#pragma once
// The plant's stem height as capture measures it (modeling/stem_height.h), from the truth: the
// straight distance from the stem's foot to the farthest base of a leaf, median over views.
#include "meadow/synth/plant_views.h"

namespace meadow::bench {

[[nodiscard]] float truthStemHeight_m(const synth::PlantTruth& truth);

}  // namespace meadow::bench
