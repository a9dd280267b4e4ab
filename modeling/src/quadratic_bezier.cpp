#include "meadow/modeling/quadratic_bezier.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace meadow::modeling {

glm::vec3 QuadraticBezier::at(float t) const {
    const float s = 1.f - t;
    return s * s * v0 + 2.f * s * t * v1 + t * t * v2;
}

glm::vec3 QuadraticBezier::tangent(float t) const {
    return 2.f * (1.f - t) * (v1 - v0) + 2.f * t * (v2 - v1);
}

float QuadraticBezier::length() const { return lengthTo(1.f); }

float QuadraticBezier::lengthTo(float t) const {
    // B'(t) = a t + b with a = 2 (v0 - 2 v1 + v2), b = 2 (v1 - v0); |B'|^2 = A t^2 + B t + C.
    // Integrated in double: the closed form cancels badly for nearly straight blades, where
    // A -> 0, so fall back to the straight-line speed there.
    const glm::dvec3 a = 2.0 * glm::dvec3(v0 - 2.f * v1 + v2);
    const glm::dvec3 b = 2.0 * glm::dvec3(v1 - v0);
    const double A = glm::dot(a, a), B = 2.0 * glm::dot(a, b), C = glm::dot(b, b);
    const double tt = std::clamp(static_cast<double>(t), 0.0, 1.0);
    if (A < 1e-12 * std::max(C, 1e-30)) return static_cast<float>(std::sqrt(C) * tt);
    const auto primitive = [&](double x) {
        // Integral of sqrt(A x^2 + B x + C) dx.
        const double q = A * x * x + B * x + C;
        const double sq = std::sqrt(std::max(q, 0.0));
        const double disc = 4.0 * A * C - B * B;  // >= 0 up to rounding (Cauchy-Schwarz)
        const double lin = (2.0 * A * x + B) * sq / (4.0 * A);
        const double arg = 2.0 * std::sqrt(A) * sq + 2.0 * A * x + B;
        if (disc <= 0.0 || arg <= 0.0) {
            // Degenerate: the control points are collinear and the speed passes through 0.
            return lin;
        }
        return lin + disc / (8.0 * A * std::sqrt(A)) * std::log(arg);
    };
    if (4.0 * A * C - B * B <= 1e-18 * A * C) {
        // Collinear control points: integrate |a x + b| piecewise, exactly.
        const double la = std::sqrt(A);
        const double root = -B / (2.0 * A);  // where the speed vanishes
        const auto absIntegral = [&](double x0, double x1) {
            const double sign = (la * (0.5 * (x0 + x1) - root)) >= 0 ? 1.0 : -1.0;
            return sign * la * (0.5 * (x1 * x1 - x0 * x0) - root * (x1 - x0));
        };
        if (root > 0.0 && root < tt)
            return static_cast<float>(absIntegral(0, root) + absIntegral(root, tt));
        return static_cast<float>(absIntegral(0, tt));
    }
    return static_cast<float>(primitive(tt) - primitive(0.0));
}

float QuadraticBezier::parameterAtLengthFraction(float fraction) const {
    const float total = length();
    const float target = std::clamp(fraction, 0.f, 1.f) * total;
    if (total <= 0.f) return fraction;
    // Bisection on the monotone arc-length function: 32 halvings reach float resolution.
    float lo = 0.f, hi = 1.f;
    for (int i = 0; i < 32; ++i) {
        const float mid = 0.5f * (lo + hi);
        (lengthTo(mid) < target ? lo : hi) = mid;
    }
    return 0.5f * (lo + hi);
}

}  // namespace meadow::modeling
