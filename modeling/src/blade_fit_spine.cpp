// Quadratic Bezier spine by least squares with parameter correction.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <string>

#include "meadow/modeling/blade_fit.h"

namespace meadow::modeling {

glm::vec3 leastSquaresMiddleControlPoint(const std::vector<glm::vec3>& points,
                                         const std::vector<float>& t, const glm::vec3& v0,
                                         const glm::vec3& v2) {
    glm::dvec3 numerator{0.0};
    double denominator = 0.0;
    for (std::size_t j = 0; j < points.size(); ++j) {
        const double tj = t[j], s = 1.0 - tj;
        const double b = 2.0 * s * tj;
        numerator +=
            b * (glm::dvec3(points[j]) - s * s * glm::dvec3(v0) - tj * tj * glm::dvec3(v2));
        denominator += b * b;
    }
    // All parameters at the ends: v1 is free; the straight line's midpoint is the natural choice.
    if (denominator <= 1e-12) return 0.5f * (v0 + v2);
    return glm::vec3(numerator / denominator);
}

SpineFit fitQuadraticBezier(const std::vector<glm::vec3>& points, int iterations) {
    const std::size_t n = points.size();
    if (n < 3)
        throw std::invalid_argument("fitQuadraticBezier: need >= 3 points, got " +
                                    std::to_string(n));
    SpineFit fit;
    fit.t.assign(n, 0.f);
    float total = 0.f;
    for (std::size_t j = 1; j < n; ++j) fit.t[j] = total += glm::distance(points[j - 1], points[j]);
    for (float& t : fit.t) t = total > 0.f ? t / total : 0.f;

    QuadraticBezier& B = fit.spine_m;
    B.v0 = points.front();
    B.v2 = points.back();
    for (int it = 0; it < iterations; ++it) {
        B.v1 = leastSquaresMiddleControlPoint(points, fit.t, B.v0, B.v2);
        const glm::vec3 second = 2.f * (B.v0 - 2.f * B.v1 + B.v2);  // B''(t), constant
        // Parameter correction: one Newton step on f(t) = (B(t) - P) . B'(t) per interior point.
        for (std::size_t j = 1; j + 1 < n; ++j) {
            const glm::vec3 r = B.at(fit.t[j]) - points[j];
            const glm::vec3 d = B.tangent(fit.t[j]);
            const float f = glm::dot(r, d);
            const float df = glm::dot(d, d) + glm::dot(r, second);
            if (df > 1e-12f) fit.t[j] = std::clamp(fit.t[j] - f / df, 0.f, 1.f);
        }
    }
    B.v1 = leastSquaresMiddleControlPoint(points, fit.t, B.v0, B.v2);
    double sum2 = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
        const float d = glm::distance(B.at(fit.t[j]), points[j]);
        sum2 += static_cast<double>(d) * d;
        fit.max_m = std::max(fit.max_m, d);
    }
    fit.rms_m = static_cast<float>(std::sqrt(sum2 / static_cast<double>(n)));
    return fit;
}

}  // namespace meadow::modeling
