#pragma once
// What a turntable gives as one library (meadow capture --turntable): its views registered to one
// another (capture/view_registration.h) against the truth's camera poses, and its library, each
// leaf's archetypes joined into its longest (modeling/view_joining.h), against the library of the
// same views captured each alone.
#include <filesystem>
#include <string>
#include <vector>

#include "meadow/modeling/archetype_library.h"
#include "meadow/modeling/capture_pipeline.h"
#include "meadow/synth/library_score.h"
#include "meadow/synth/plant_views.h"

namespace meadow::bench {

// One library's share of the plant: leaves (counted in some view) it holds, archetypes matching
// a leaf and matching none, and per held leaf the median length error of its archetypes.
struct HeldLeaves {
    int archetypes = 0, held = 0, matching = 0, falseBlades = 0;
    int counted = 0;  // leaves counted in some view (0 for an empty library, not scored)
    std::vector<float> lengthError;
    void add(const HeldLeaves& o);
};

struct TurntableRow {
    std::string sensor, plant;
    // The recording's views after the first, and of them those capture registered.
    int pairs = 0, registered = 0;
    // Of the pairs, those whose plant's own readings (the truth's leaf and stem pixels) lie on
    // the view before's at the true turn as registration asks: what the sensor allows.
    int registrable = 0;
    // Per registered view: the angle between the estimated and the true turn from the chain's
    // first view (degrees), and how far the estimate puts the view's true leaf points from where
    // the truth puts them (mean, mm).
    std::vector<float> turnError_deg, offset_mm;
    int leaves = 0;  // counted in some view
    HeldLeaves eachView, joined;
    // Per view, the capture's time (ms, its total over its views): the views captured each alone,
    // and the turntable's (registration and joining besides), taken one after the other.
    std::vector<double> eachView_ms, turntable_ms;
    void add(const TurntableRow& o);
};

// `recording`: the turntable's folder (its depth frames); `registration`: what capture
// registered with, for the registrable pairs.
TurntableRow scoreTurntable(const modeling::ArchetypeLibrary& eachView,
                            const modeling::CaptureResult& turntable,
                            const synth::PlantTruth& truth, const synth::ScoringTruth& scoring,
                            const std::filesystem::path& recording,
                            const capture::ViewRegistrationParams& registration);

// The section of plant_benchmark.md: a paragraph and one row per plant and sensor, and all.
std::string turntableSection(const std::vector<TurntableRow>& rows);
// The same rows as CSV (plant_turntable.csv), with a header line.
std::string turntableCsv(const std::vector<TurntableRow>& rows);

}  // namespace meadow::bench
