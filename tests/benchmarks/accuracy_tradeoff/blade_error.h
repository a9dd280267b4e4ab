#pragma once
// How far a fitted blade is from its true blade, and a tuft's capture scored against the truth
// (accuracy / trade-off bench).
#include <limits>
#include <vector>

#include "accuracy_tradeoff/scene.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::bench {

struct BladeError {
    float v0_mm = 0.f, v1_mm = 0.f, v2_mm = 0.f;  // control points, camera space
    float heightError = 0.f;                      // (fitted - true) / true, signed
    float widthMaeFraction = 0.f;                 // mean |w_fit(s) - w_true(s)| / max true width
    float offCurve_mm = 0.f;  // largest distance of the fitted spine from the true spine curve
    // Largest distance of the refined-knot polyline from it; NaN when refining was off.
    float knotPolyline_mm = std::numeric_limits<float>::quiet_NaN();
    float baseS = 0.f, tipS = 0.f;  // arc fraction of the true spine nearest the fitted v0 / v2
    [[nodiscard]] float controlPointMean_mm() const { return (v0_mm + v1_mm + v2_mm) / 3.f; }
};

BladeError bladeError(const modeling::BladeFit& fit, const synth::SyntheticBlade& truth);

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
