#pragma once
// The partition's bound: every view's leaves cut as the truth cuts them (each leaf's own pixels
// among those the sensor read, its base and tip where its true centre line starts and ends),
// then modelled as capture models a blade. What this library misses, a perfect partition would
// miss too: the sensor did not show the leaf well enough, or the model cannot hold it.
// WhereItStarts carries each leaf down to where its true centre line starts (as a tuft's blade is
// carried to the tuft's base), hidden or not; LowestSeen models it as far down as the sensor read
// it, as capture models a leaf it cut from a stem: the length no partition passes without
// guessing where a hidden base lies.
#include <filesystem>

#include "meadow/modeling/archetype_library.h"
#include "meadow/modeling/capture_pipeline.h"
#include "meadow/synth/library_score.h"

namespace meadow::bench {

enum class TruthBase { WhereItStarts, LowestSeen };

[[nodiscard]] modeling::ArchetypeLibrary modelTruthLeaves(const std::filesystem::path& recording,
                                                          const synth::ScoringTruth& truth,
                                                          const modeling::CaptureOptions& options,
                                                          TruthBase base);

}  // namespace meadow::bench
