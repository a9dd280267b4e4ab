// A closed mesh as spheres for collisions (sphere_packing.h), against shapes whose inside is
// known exactly: a ball is one sphere of its radius; a capsule is covered by spheres that stay
// inside it; a flat square encloses nothing and is refused.
#include "sphere_packing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <random>

#include "collider_shapes.h"
#include "meadow/runtime/error.h"

namespace meadow::runtime {
namespace {

constexpr float kCapsuleRadius_m = 0.18f, kCapsuleHalfLength_m = 0.35f;

// Signed distance to the capsule along X (negative inside).
float capsuleDistance_m(glm::vec3 p) {
    const float x = std::clamp(p.x, -kCapsuleHalfLength_m, kCapsuleHalfLength_m);
    return glm::length(p - glm::vec3(x, 0.f, 0.f)) - kCapsuleRadius_m;
}

// The capsule as a closed mesh: the unit sphere's rings stretched apart at the equator.
TriangleMesh capsuleMesh() {
    TriangleMesh m = sphereMesh(kCapsuleRadius_m, 16, 32);
    for (glm::vec3& p : m.positions_m)
        p.x += p.x >= 0.f ? kCapsuleHalfLength_m : -kCapsuleHalfLength_m;
    return m;
}

TEST(SpherePacking, ABallIsOneSphereOfItsRadius) {
    const SpherePacking packed = packSpheres(sphereMesh(0.3f, 24, 48));
    ASSERT_FALSE(packed.spheres.empty());
    const CollisionSphere& s = packed.spheres.front();
    EXPECT_LT(glm::length(s.center_m), packed.voxel_m);
    EXPECT_NEAR(s.radius_m, 0.3f, 1.5f * packed.voxel_m);
    EXPECT_GE(packed.coverage, 0.97f);
    EXPECT_LE(packed.spheres.size(), 4u) << "a ball needs its one sphere and a few for the rim";
}

TEST(SpherePacking, ACapsuleIsCoveredBySpheresThatStayInside) {
    const SpherePacking packed = packSpheres(capsuleMesh(), {.maxSpheres = 32});
    ASSERT_GE(packed.spheres.size(), 3u);
    ASSERT_LE(packed.spheres.size(), 32u);
    for (const CollisionSphere& s : packed.spheres)
        EXPECT_LE(capsuleDistance_m(s.center_m) + s.radius_m, packed.voxel_m)
            << "sphere at " << s.center_m.x << ", " << s.center_m.y << ", " << s.center_m.z
            << " radius " << s.radius_m << " reaches out of the capsule";
    // Points well inside (2 cm from the surface) are inside some sphere.
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> x(-0.55f, 0.55f), yz(-0.2f, 0.2f);
    int inside = 0, covered = 0;
    while (inside < 2000) {
        const glm::vec3 p{x(rng), yz(rng), yz(rng)};
        if (capsuleDistance_m(p) > -0.02f) continue;
        ++inside;
        for (const CollisionSphere& s : packed.spheres)
            if (glm::distance(p, s.center_m) <= s.radius_m) {
                ++covered;
                break;
            }
    }
    EXPECT_GE(covered, 0.95 * inside) << covered << " of " << inside;
}

TEST(SpherePacking, AFlatSquareEnclosesNothingAndIsRefused) {
    TriangleMesh square;
    square.origin = "square.gltf";
    square.positions_m = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {1, 0, 1}};
    square.normals.assign(4, {0, 1, 0});
    square.triangles = {{0, 2, 1}, {1, 2, 3}};
    try {
        (void)packSpheres(square);
        FAIL() << "a flat square has no volume";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("square.gltf"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace meadow::runtime
