#pragma once
// A tuft's capture scored against the truth (accuracy / trade-off bench); how far each fitted
// blade lies from its true one is synth::bladeError.
#include <vector>

#include "accuracy_tradeoff/scene.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/synth/blade_error.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::bench {

using synth::BladeError;
using synth::bladeError;

// Fitted blades matched one-to-one to true blades by label IoU (>= kMatchIou); the rest counted.
struct TuftScore {
    int trueBlades = 0;       // visible true blades
    int found = 0;            // blades the segmenter returned
    int fitted = 0;           // archetypes the capture produced
    int fittedMatched = 0;    // ... of which match a true blade
    int fitFailures = 0;      // fitBlade threw
    std::vector<double> iou;  // per visible true blade
    std::vector<BladeError> errors;
    std::vector<const modeling::BladeFit*>
        matchedFits;  // parallel to errors (valid while capture lives)
};

TuftScore scoreCapture(const Scene& scene, const TuftCapture& cap);

}  // namespace meadow::bench
