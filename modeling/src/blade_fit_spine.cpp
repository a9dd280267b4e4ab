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

// Newton steps on the parameters between two control point updates. The alternation converges
// linearly; several parameter steps per solve make each outer iteration count.
constexpr int kNewtonStepsPerIteration = 3;
// Weight of the plain least-squares term in the control point update (stepControlPoints).
constexpr double kRegularisation = 1e-3;

// Point j's weight in every sum of the fit (empty weights: all 1). Anything not above 0, NaN
// included, leaves the point out.
double weightOf(const std::vector<float>& weights, std::size_t j) {
    const double w = weights.empty() ? 1.0 : weights[j];
    return w > 0.0 ? w : 0.0;
}

}  // namespace

glm::vec3 leastSquaresMiddleControlPoint(const std::vector<glm::vec3>& points,
                                         const std::vector<float>& t, const glm::vec3& v0,
                                         const glm::vec3& v2, const std::vector<float>& weights) {
    glm::dvec3 numerator{0.0};
    double denominator = 0.0;
    for (std::size_t j = 0; j < points.size(); ++j) {
        const double w = weightOf(weights, j);
        if (w == 0.0) continue;
        const double tj = t[j], s = 1.0 - tj;
        const double b = 2.0 * s * tj;
        numerator +=
            w * b * (glm::dvec3(points[j]) - s * s * glm::dvec3(v0) - tj * tj * glm::dvec3(v2));
        denominator += w * b * b;
    }
    // All parameters at the ends: v1 is free; the straight line's midpoint is the natural choice.
    if (denominator <= 1e-12) return 0.5f * (v0 + v2);
    return glm::vec3(numerator / denominator);
}

namespace {

// The residual of point j minus, where its parameter can still slide along the curve, the part
// along the tangent: at the closest point that part is absorbed by t (tangent distance
// minimisation, Wang, Pottmann & Liu 2006, Sec. 4). A point held at an end of the curve (the first
// or last point where that end is fitted, a point whose closest parameter is clamped to 0 or 1)
// cannot slide, so all of its residual counts: without that a fitted end could retract past such
// points for free.
glm::dmat3 residualProjector(const QuadraticBezier& B, float t, bool atEnd) {
    if (atEnd) return glm::dmat3(1.0);
    const glm::dvec3 d{B.tangent(t)};
    const double dLen = glm::length(d);
    const glm::dvec3 u = dLen > 0.0 ? d / dLen : glm::dvec3(0.0);
    return glm::dmat3(1.0) - glm::outerProduct(u, u);
}

// One Gauss-Newton step on the free control points: v1 always, v2 unless the ends are pinned, v0
// when both ends are fitted. B(t_j) = (1 - t_j)^2 v0 + 2 (1 - t_j) t_j v1 + t_j^2 v2 is linear in
// them, so the normal equations are sums of 3x3 blocks w_a w_b P_j over the free points' Bernstein
// weights w. A small multiple of the plain least-squares term keeps the system regular for a
// straight spine, whose tangents are all parallel. False when no point constrains the step.
bool stepControlPoints(const std::vector<glm::vec3>& points, const std::vector<float>& t,
                       const std::vector<float>& weights, SpineEnds ends, QuadraticBezier& B) {
    const std::size_t n = points.size();
    const bool fitRoot = ends == SpineEnds::Fitted, fitTip = ends != SpineEnds::AtEndPoints;
    std::vector<int> free;  // control point indices
    if (fitRoot) free.push_back(0);
    free.push_back(1);
    if (fitTip) free.push_back(2);
    const int size = 3 * static_cast<int>(free.size());
    cv::Mat1d A(size, size, 0.0), g(size, 1, 0.0);
    double diagonal = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
        const bool first = j == 0, last = j + 1 == n;
        // A pinned end's point is the control point itself: it has no residual.
        if ((first && !fitRoot) || (last && !fitTip)) continue;
        const double weight = weightOf(weights, j);
        if (weight == 0.0) continue;
        const double tj = t[j];
        const double bernstein[3] = {(1.0 - tj) * (1.0 - tj), 2.0 * (1.0 - tj) * tj, tj * tj};
        const glm::dmat3 P =
            weight * residualProjector(B, t[j], first || last || t[j] <= 0.f || t[j] >= 1.f);
        const glm::dvec3 Pr = P * glm::dvec3(B.at(t[j]) - points[j]);
        for (std::size_t a = 0; a < free.size(); ++a) {
            const double wa = bernstein[free[a]];
            for (int row = 0; row < 3; ++row) {
                g(3 * static_cast<int>(a) + row) += wa * Pr[row];
                for (std::size_t b = 0; b < free.size(); ++b)
                    for (int col = 0; col < 3; ++col)
                        A(3 * static_cast<int>(a) + row, 3 * static_cast<int>(b) + col) +=
                            wa * bernstein[free[b]] * P[col][row];
            }
            diagonal += weight * wa * wa;
        }
    }
    if (diagonal <= 0.0) return false;
    A += cv::Mat1d::eye(size, size) * (kRegularisation * diagonal);
    cv::Mat1d step;
    if (!cv::solve(A, g, step, cv::DECOMP_CHOLESKY)) return false;
    glm::vec3* control[3] = {&B.v0, &B.v1, &B.v2};
    for (std::size_t a = 0; a < free.size(); ++a)
        *control[free[a]] -=
            glm::vec3(step(3 * static_cast<int>(a)), step(3 * static_cast<int>(a) + 1),
                      step(3 * static_cast<int>(a) + 2));
    return true;
}

}  // namespace

SpineFit fitQuadraticBezier(const std::vector<glm::vec3>& points, int iterations, SpineEnds ends,
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
    B.v1 = leastSquaresMiddleControlPoint(points, fit.t, B.v0, B.v2, weights);
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
        if (!stepControlPoints(points, fit.t, weights, ends, B)) break;
    }
    double sum2 = 0.0, weightSum = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
        const double w = weightOf(weights, j);
        if (w == 0.0) continue;
        const float d = glm::distance(B.at(fit.t[j]), points[j]);
        sum2 += w * d * d;
        weightSum += w;
        fit.max_m = std::max(fit.max_m, d);
    }
    fit.rms_m = weightSum > 0.0 ? static_cast<float>(std::sqrt(sum2 / weightSum)) : 0.f;
    return fit;
}

}  // namespace meadow::modeling
