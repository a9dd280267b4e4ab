#include "meadow/modeling/blade_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

using namespace meadow::modeling;

namespace {

// A bent blade with a leaf-like profile: 11 samples, so 40 segments hit every sample.
Archetype leaf() {
    Archetype a;
    a.name = "leaf";
    a.spine_m = {{0, 0, 0}, {0, 0.1f, 0}, {0.06f, 0.14f, 0}};
    a.width.width_m = {0.008f, 0.012f, 0.015f, 0.016f, 0.016f, 0.015f,
                       0.013f, 0.011f, 0.008f, 0.004f, 0.f};
    return a;
}

// Exact integral of the piecewise-linear width over arc length (trapezoids on its samples).
double widthIntegral_m2(const Archetype& a) {
    const auto& w = a.width.width_m;
    double sum = 0;
    for (std::size_t i = 0; i + 1 < w.size(); ++i) sum += 0.5 * (w[i] + w[i + 1]);
    return sum / static_cast<double>(w.size() - 1) * a.spine_m.length();
}

}  // namespace

TEST(BladeMesh, SurfaceAreaEqualsTheIntegralOfWidthAlongTheSpine) {
    const Archetype a = leaf();
    BladeMeshOptions options;
    options.segments = 40;
    const TriangleMesh mesh = bladeMesh(a, options);
    // Chords cut the bend's corners: the area converges to the integral as segments grow.
    EXPECT_NEAR(mesh.surfaceArea_m2(), widthIntegral_m2(a), 0.002 * widthIntegral_m2(a))
        << "height " << a.height_m();
}

TEST(BladeMesh, RingMidpointsLieOnTheBezierAtEqualArcLength) {
    const Archetype a = leaf();
    BladeMeshOptions options;
    options.segments = 16;
    const TriangleMesh mesh = bladeMesh(a, options);
    ASSERT_EQ(mesh.positions_m.size(), 2u * (options.segments + 1));
    for (int i = 0; i <= options.segments; ++i) {
        const float s = static_cast<float>(i) / options.segments;
        const glm::vec3 mid = 0.5f * (mesh.positions_m[2 * i] + mesh.positions_m[2 * i + 1]);
        const float t = a.spine_m.parameterAtLengthFraction(s);
        EXPECT_LT(glm::length(mid - a.spine_m.at(t)), 1e-6f) << "ring " << i;
        EXPECT_NEAR(a.spine_m.lengthTo(t), s * a.height_m(), 1e-6f) << "ring " << i;
    }
}

TEST(BladeMesh, WidthIsAcrossTheSpineInTheFacePlaneWithFaceNormalPlusZ) {
    const Archetype a = leaf();
    const TriangleMesh mesh = bladeMesh(a);
    const int segments = BladeMeshOptions{}.segments;
    for (int i = 0; i <= segments; ++i) {
        const float s = static_cast<float>(i) / segments;
        const float t = a.spine_m.parameterAtLengthFraction(s);
        const glm::vec3 across = mesh.positions_m[2 * i + 1] - mesh.positions_m[2 * i];
        EXPECT_NEAR(glm::length(across), a.width.at(s), 1e-6f) << "ring " << i;
        EXPECT_NEAR(glm::dot(across, glm::normalize(a.spine_m.tangent(t))), 0.f, 1e-6f);
        EXPECT_NEAR(across.z, 0.f, 1e-7f);
        EXPECT_NEAR(glm::length(mesh.normals[2 * i] - glm::vec3(0, 0, 1)), 0.f, 1e-6f);
    }
    for (const glm::uvec3& tri : mesh.triangles) {  // counter-clockwise seen from +Z
        const glm::vec3 n = glm::cross(mesh.positions_m[tri.y] - mesh.positions_m[tri.x],
                                       mesh.positions_m[tri.z] - mesh.positions_m[tri.x]);
        EXPECT_GT(n.z, 0.f);
    }
}

TEST(BladeMesh, LeftWidthFractionSplitsTheWidthUnevenly) {
    Archetype a = leaf();
    a.leftWidthFraction = 0.25f;
    BladeMeshOptions options;
    options.segments = 10;
    const TriangleMesh mesh = bladeMesh(a, options);
    for (int i = 0; i <= options.segments; ++i) {
        const float s = static_cast<float>(i) / options.segments;
        const glm::vec3 p = a.spine_m.at(a.spine_m.parameterAtLengthFraction(s));
        EXPECT_NEAR(glm::length(mesh.positions_m[2 * i] - p), 0.25f * a.width.at(s), 1e-6f);
        EXPECT_NEAR(glm::length(mesh.positions_m[2 * i + 1] - p), 0.75f * a.width.at(s), 1e-6f);
    }
    // Most of the width now lies on the inside of the bend (+X), where the ribbon is compressed
    // by the curvature: a little less area than the symmetric blade, never more.
    const float symmetric_m2 = bladeMesh(leaf(), {10}).surfaceArea_m2();
    EXPECT_LT(mesh.surfaceArea_m2(), symmetric_m2);
    EXPECT_GT(mesh.surfaceArea_m2(), 0.95f * symmetric_m2);
}

TEST(BladeMesh, TwistTurnsTheTipOutOfTheFacePlaneButKeepsTheWidth) {
    Archetype a = leaf();
    a.twistAtTip_rad = 1.0f;
    const BladeMeshOptions options;
    const TriangleMesh mesh = bladeMesh(a, options);
    const int last = options.segments - 1;  // the tip ring has zero width
    const glm::vec3 across = mesh.positions_m[2 * last + 1] - mesh.positions_m[2 * last];
    const float s = static_cast<float>(last) / options.segments;
    EXPECT_NEAR(glm::length(across), a.width.at(s), 1e-6f);
    EXPECT_GT(std::abs(across.z), 0.5f * glm::length(across)) << "twist at s " << s;
}

TEST(BladeMesh, TransformedMeshKeepsAreaAndUnitNormals) {
    const TriangleMesh local = bladeMesh(leaf());
    glm::mat4 cameraFromBlade = glm::translate(glm::mat4(1.f), glm::vec3(0.1f, 0.2f, 0.8f));
    cameraFromBlade = glm::rotate(cameraFromBlade, 0.7f, glm::normalize(glm::vec3(1, 2, 3)));
    const TriangleMesh moved = transformed(local, cameraFromBlade);
    EXPECT_NEAR(moved.surfaceArea_m2(), local.surfaceArea_m2(), 1e-7f);
    EXPECT_NEAR(glm::length(moved.normals[0]), 1.f, 1e-6f);
}

TEST(BladeMesh, RejectsBrokenPreconditions) {
    Archetype a = leaf();
    EXPECT_THROW((void)bladeMesh(a, {0}), std::invalid_argument);
    Archetype lopsided = a;
    lopsided.leftWidthFraction = 1.5f;
    EXPECT_THROW((void)bladeMesh(lopsided, {8}), std::invalid_argument);
    a.spine_m = {};
    EXPECT_THROW((void)bladeMesh(a), std::invalid_argument);
}
