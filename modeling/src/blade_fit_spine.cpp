// Quadratic Bezier spine by least squares with parameter correction.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <opencv2/core.hpp>
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

namespace {

// The residual of point j minus, where its parameter can still slide along the curve, the part
// along the tangent: at the closest point that part is absorbed by t (tangent distance
// minimisation, Wang, Pottmann & Liu 2006, Sec. 4). A point held at an end of the curve (the last
// point with a free tip, a point whose closest parameter is clamped to 0 or 1) cannot slide, so
// all of its residual counts: without that a free tip could retract past such points for free.
glm::dmat3 residualProjector(const QuadraticBezier& B, float t, bool atEnd) {
    if (atEnd) return glm::dmat3(1.0);
    const glm::dvec3 d{B.tangent(t)};
    const double dLen = glm::length(d);
    const glm::dvec3 u = dLen > 0.0 ? d / dLen : glm::dvec3(0.0);
    return glm::dmat3(1.0) - glm::outerProduct(u, u);
}

// One Gauss-Newton step on v1 alone (v0 and v2 fixed at the ends). A small multiple of the plain
// least-squares term keeps the 3x3 system regular for a straight spine, whose tangents are all
// parallel. False when no interior point constrains v1.
bool stepMiddleControlPoint(const std::vector<glm::vec3>& points, const std::vector<float>& t,
                            const std::vector<float>& weights, QuadraticBezier& B) {
    glm::dmat3 A{0.0};
    glm::dvec3 g{0.0};
    double bSum = 0.0;
    for (std::size_t j = 1; j + 1 < points.size(); ++j) {
        const double b = 2.0 * (1.0 - t[j]) * t[j];
        const double w = weights.empty() ? 1.0 : weights[j];
        const glm::dmat3 P = residualProjector(B, t[j], t[j] <= 0.f || t[j] >= 1.f);
        const glm::dvec3 r{B.at(t[j]) - points[j]};
        A += w * b * b * P;
        g += w * b * (P * r);
        bSum += w * b * b;
    }
    if (bSum <= 0.0) return false;
    A += kRegularisation * bSum * glm::dmat3(1.0);
    B.v1 -= glm::vec3(glm::inverse(A) * g);
    return true;
}

// One Gauss-Newton step on v1 and v2 together (v0 fixed at the root): the residual of point j is
// linear in them, B(t_j) = (1 - t_j)^2 v0 + b_j v1 + t_j^2 v2, so the 6x6 normal equations are
// sums of the 3x3 blocks w_a w_b P_j with w = (b_j, t_j^2). The last point keeps t = 1.
bool stepMiddleAndTip(const std::vector<glm::vec3>& points, const std::vector<float>& t,
                      const std::vector<float>& weights, QuadraticBezier& B) {
    cv::Matx66d A = cv::Matx66d::zeros();
    cv::Vec6d g = cv::Vec6d::all(0.0);
    double diagonal = 0.0;
    for (std::size_t j = 1; j < points.size(); ++j) {
        const double w[2] = {2.0 * (1.0 - t[j]) * t[j], static_cast<double>(t[j]) * t[j]};
        const double weight = weights.empty() ? 1.0 : weights[j];
        if (weight <= 0.0) continue;
        const glm::dmat3 P =
            weight *
            residualProjector(B, t[j], j + 1 == points.size() || t[j] <= 0.f || t[j] >= 1.f);
        const glm::dvec3 Pr = P * glm::dvec3(B.at(t[j]) - points[j]);
        for (int a = 0; a < 2; ++a)
            for (int row = 0; row < 3; ++row) {
                g[3 * a + row] += w[a] * Pr[row];
                for (int b = 0; b < 2; ++b)
                    for (int col = 0; col < 3; ++col)
                        A(3 * a + row, 3 * b + col) += w[a] * w[b] * P[col][row];
            }
        diagonal += weight * (w[0] * w[0] + w[1] * w[1]);
    }
    if (diagonal <= 0.0) return false;
    for (int i = 0; i < 6; ++i) A(i, i) += kRegularisation * diagonal;
    cv::Vec6d step;
    if (!cv::solve(A, g, step, cv::DECOMP_CHOLESKY)) return false;
    B.v1 -= glm::vec3(step[0], step[1], step[2]);
    B.v2 -= glm::vec3(step[3], step[4], step[5]);
    return true;
}

}  // namespace

SpineFit fitQuadraticBezier(const std::vector<glm::vec3>& points, int iterations, SpineTip tip,
                            const std::vector<float>& weights) {
    const std::size_t n = points.size();
    if (n < 3)
        throw std::invalid_argument("fitQuadraticBezier: need >= 3 points, got " +
                                    std::to_string(n));
    if (!weights.empty() && weights.size() != n)
        throw std::invalid_argument("fitQuadraticBezier: " + std::to_string(weights.size()) +
                                    " weights for " + std::to_string(n) + " points");
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
        // Control point update. Alternating the closed form above with the parameter correction
        // converges only linearly (slowly when the chord parameters are far off), so the update
        // minimises the squared distances to the curve to first order instead (Gauss-Newton with
        // the residuals' tangential parts left out where t absorbs them, residualProjector).
        const bool moved = tip == SpineTip::LeastSquares
                               ? stepMiddleAndTip(points, fit.t, weights, B)
                               : stepMiddleControlPoint(points, fit.t, weights, B);
        if (!moved) break;
    }
    double sum2 = 0.0, weightSum = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
        const double w = weights.empty() ? 1.0 : weights[j];
        if (w <= 0.0) continue;
        const float d = glm::distance(B.at(fit.t[j]), points[j]);
        sum2 += w * d * d;
        weightSum += w;
        fit.max_m = std::max(fit.max_m, d);
    }
    fit.rms_m = weightSum > 0.0 ? static_cast<float>(std::sqrt(sum2 / weightSum)) : 0.f;
    return fit;
}

}  // namespace meadow::modeling
