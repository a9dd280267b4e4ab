// Quadratic Bezier spine by least squares with parameter correction.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <stdexcept>
#include <string>

#include "meadow/modeling/blade_fit.h"

namespace meadow::modeling {
namespace {

// Newton steps on the parameters between two solves for v1. The alternation converges linearly;
// several parameter steps per solve make each outer iteration count.
constexpr int kNewtonStepsPerIteration = 3;
// Weight of the plain least-squares term in the v1 update (see fitQuadraticBezier).
constexpr double kRegularisation = 1e-3;

}  // namespace

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
    B.v1 = leastSquaresMiddleControlPoint(points, fit.t, B.v0, B.v2);
    for (int it = 0; it < iterations; ++it) {
        // Parameter correction: Newton steps on f(t) = (B(t) - P) . B'(t) per interior point.
        const glm::vec3 second = 2.f * (B.v0 - 2.f * B.v1 + B.v2);  // B''(t), constant
        for (int step = 0; step < kNewtonStepsPerIteration; ++step) {
            for (std::size_t j = 1; j + 1 < n; ++j) {
                const glm::vec3 r = B.at(fit.t[j]) - points[j];
                const glm::vec3 d = B.tangent(fit.t[j]);
                const float f = glm::dot(r, d);
                const float df = glm::dot(d, d) + glm::dot(r, second);
                if (df > 1e-12f) fit.t[j] = std::clamp(fit.t[j] - f / df, 0.f, 1.f);
            }
        }
        // Update of v1. Alternating the closed form above with the parameter correction converges
        // only linearly (slowly when the chord parameters are far off), so the update minimises the
        // squared distances to the curve to first order instead: with the parameters at the
        // closest points the residual's tangential part is absorbed by t, which leaves the normal
        // part, J_j = b_j (I - u_j u_j^T) (tangent distance minimisation, Wang, Pottmann & Liu
        // 2006, Sec. 4). A small multiple of the plain least-squares term keeps the 3x3 system
        // regular for a straight spine, whose tangents are all parallel.
        glm::dmat3 A{0.0};
        glm::dvec3 g{0.0};
        double bSum = 0.0;
        for (std::size_t j = 1; j + 1 < n; ++j) {
            const double tj = fit.t[j];
            const double b = 2.0 * (1.0 - tj) * tj;
            const glm::dvec3 d{B.tangent(fit.t[j])};
            const double dLen = glm::length(d);
            const glm::dvec3 u = dLen > 0.0 ? d / dLen : glm::dvec3(0.0);
            const glm::dmat3 normalProjector = glm::dmat3(1.0) - glm::outerProduct(u, u);
            const glm::dvec3 r{B.at(fit.t[j]) - points[j]};
            A += b * b * normalProjector;
            g += b * (normalProjector * r);
            bSum += b * b;
        }
        if (bSum <= 0.0) break;
        A += kRegularisation * bSum * glm::dmat3(1.0);
        B.v1 -= glm::vec3(glm::inverse(A) * g);
    }
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
