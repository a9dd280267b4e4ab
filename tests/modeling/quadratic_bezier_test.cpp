#include "meadow/modeling/quadratic_bezier.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

using meadow::modeling::QuadraticBezier;

namespace {
// Reference arc length by a fine polyline (converges as 1/n^2), evaluated in double: float
// points would carry more rounding than the 1e-6 m segments are long.
double polylineLength(const QuadraticBezier& c, int n = 200000) {
    const glm::dvec3 v0 = c.v0, v1 = c.v1, v2 = c.v2;
    const auto at = [&](double t) {
        return (1 - t) * (1 - t) * v0 + 2 * (1 - t) * t * v1 + t * t * v2;
    };
    double sum = 0;
    glm::dvec3 prev = at(0.0);
    for (int i = 1; i <= n; ++i) {
        const glm::dvec3 p = at(static_cast<double>(i) / n);
        sum += glm::length(p - prev);
        prev = p;
    }
    return sum;
}
}  // namespace

TEST(QuadraticBezier, EndpointsAreTheOuterControlPoints) {
    const QuadraticBezier c{{0, 0, 0}, {0, 0.1f, 0}, {0.05f, 0.15f, 0.02f}};
    EXPECT_EQ(c.at(0.f), c.v0);
    EXPECT_EQ(c.at(1.f), c.v2);
}

TEST(QuadraticBezier, ClosedFormLengthMatchesAFinePolyline) {
    const QuadraticBezier bent{{0, 0, 0}, {0, 0.12f, 0}, {0.08f, 0.14f, 0.01f}};
    const QuadraticBezier straight{{0, 0, 0}, {0, 0.05f, 0}, {0, 0.1f, 0}};
    const QuadraticBezier cusp{{0, 0, 0}, {0, 0.2f, 0}, {0, 0.05f, 0}};  // folds back on itself
    for (const auto& c : {bent, straight, cusp}) {
        EXPECT_NEAR(c.length(), polylineLength(c), 1e-6) << "v1 " << c.v1.y << " v2 " << c.v2.y;
    }
    EXPECT_NEAR(straight.length(), 0.1f, 1e-7f);
}

TEST(QuadraticBezier, ParameterAtLengthFractionInvertsLengthTo) {
    const QuadraticBezier c{{0, 0, 0}, {0, 0.12f, 0}, {0.08f, 0.14f, 0.01f}};
    for (float f : {0.f, 0.1f, 0.5f, 0.9f, 1.f}) {
        const float t = c.parameterAtLengthFraction(f);
        EXPECT_NEAR(c.lengthTo(t), f * c.length(), 1e-6f) << "fraction " << f;
    }
}
