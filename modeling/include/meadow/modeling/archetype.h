#pragma once
// A blade archetype: the product of capture and the input of the renderer.
//
// Blade-local frame (metres): v0 at the origin, +Y up along the base direction, the blade's face
// approximately in the XY plane (face normal +Z), the spine bending within that plane toward +X
// (a captured spine may carry a small Z component from depth). The width at arc-length fraction
// s is measured in the face plane, perpendicular to the spine's tangent.
#include <string>
#include <vector>

#include "meadow/modeling/quadratic_bezier.h"

namespace meadow::modeling {

// Nearest analytic blade shape of Jahrmann & Wimmer 2017, Sec. 6.2 (their Fig. 6).
enum class AnalyticShape { Quad, Triangle, Quadratic, TriangleTip };

struct WidthProfile {
    // Full width (m) at evenly spaced arc-length fractions s_i = i / (n - 1), s = 0 at the base,
    // s = 1 at the tip; n >= 2. Linear in between.
    std::vector<float> width_m;

    [[nodiscard]] float at(float s) const;  // linear interpolation, s clamped to [0, 1]
    [[nodiscard]] float maxWidth_m() const;
};

struct Archetype {
    std::string name;
    QuadraticBezier spine_m;  // blade-local frame above
    WidthProfile width;
    AnalyticShape nearestShape = AnalyticShape::Quadratic;
    float tau = 0.5f;  // triangle-tip parameter (fraction of height where the tip begins)

    // Arc length of the spine (the blade's height when straightened).
    [[nodiscard]] float height_m() const { return spine_m.length(); }
};

}  // namespace meadow::modeling
