#pragma once
// A quadratic Bézier curve B(t) = (1-t)^2 v0 + 2(1-t)t v1 + t^2 v2, t in [0, 1]: the blade
// spine of Jahrmann & Wimmer 2017 (v0 root, v1 middle control point, v2 tip).
#include <glm/vec3.hpp>

namespace meadow::modeling {

struct QuadraticBezier {
    glm::vec3 v0{0.f};
    glm::vec3 v1{0.f};
    glm::vec3 v2{0.f};

    [[nodiscard]] glm::vec3 at(float t) const;
    [[nodiscard]] glm::vec3 tangent(float t) const;  // dB/dt, not normalised
    // Arc length, exact to float precision (closed form of the integral of |B'(t)|).
    [[nodiscard]] float length() const;
    // Arc length from 0 to t.
    [[nodiscard]] float lengthTo(float t) const;
    // Parameter t at which the arc length from v0 equals fraction * length(), fraction in [0,1].
    [[nodiscard]] float parameterAtLengthFraction(float fraction) const;
};

}  // namespace meadow::modeling
