#pragma once
// How far a fitted blade lies from its true blade, in camera space.
#include <limits>

#include "meadow/modeling/blade_fit.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::synth {

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

[[nodiscard]] BladeError bladeError(const modeling::BladeFit& fit, const SyntheticBlade& truth);

}  // namespace meadow::synth
