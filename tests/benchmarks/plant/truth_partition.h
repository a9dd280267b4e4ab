#pragma once
// The partition's bound: every view's leaves cut as the truth cuts them (each leaf's own pixels
// among those the sensor read, its base and tip where its true centre line starts and ends),
// then modelled as capture models a blade. What this library misses, a perfect partition would
// miss too: the sensor did not show the leaf well enough, or the model cannot hold it.
#include <filesystem>

#include "meadow/modeling/archetype_library.h"
#include "meadow/modeling/capture_pipeline.h"
#include "meadow/synth/library_score.h"

namespace meadow::bench {

[[nodiscard]] modeling::ArchetypeLibrary modelTruthLeaves(const std::filesystem::path& recording,
                                                          const synth::ScoringTruth& truth,
                                                          const modeling::CaptureOptions& options);

}  // namespace meadow::bench
