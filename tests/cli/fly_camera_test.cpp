// `meadow view`'s fly camera: where keys move it and how the mouse turns it, without a window.
#include "fly_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <string>

using meadow::cli::FlyCamera;

namespace {

constexpr float kTolerance_m = 1e-5f;

std::string text(glm::vec3 v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) +
           ")";
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance) {
    EXPECT_LT(glm::length(actual - expected), tolerance)
        << "actual " << text(actual) << " expected " << text(expected);
}

TEST(FlyCamera, StartsLookingAtItsTarget) {
    const glm::vec3 position_m{0.f, 1.6f, 5.5f}, target_m{0.f, 0.2f, 0.f};
    const FlyCamera camera = FlyCamera::lookingAt(position_m, target_m);
    expectNear(camera.position_m(), position_m, kTolerance_m);
    expectNear(camera.forward(), glm::normalize(target_m - position_m), kTolerance_m);
    EXPECT_NEAR(glm::length(camera.forward()), 1.f, kTolerance_m);
}

TEST(FlyCamera, ForwardMovesAlongTheViewDirectionIncludingPitch) {
    const glm::vec3 position_m{1.f, 2.f, 3.f}, target_m{4.f, 0.f, -1.f};
    FlyCamera camera = FlyCamera::lookingAt(position_m, target_m);
    camera.move({0.f, 0.f, 1.f}, 0.5f);
    expectNear(camera.position_m(), position_m + 0.5f * glm::normalize(target_m - position_m),
               kTolerance_m);
    camera.move({0.f, 0.f, -1.f}, 0.5f);  // S undoes W
    expectNear(camera.position_m(), position_m, kTolerance_m);
}

TEST(FlyCamera, StrafesHorizontallyToTheRightAndRisesAlongWorldUp) {
    FlyCamera camera = FlyCamera::lookingAt({0.f, 0.f, 0.f}, {0.f, -1.f, -1.f});  // looking down
    camera.move({1.f, 0.f, 0.f}, 2.f);
    expectNear(camera.position_m(), {2.f, 0.f, 0.f}, kTolerance_m);  // -Z view: right is +X
    camera.move({0.f, 1.f, 0.f}, 1.f);
    expectNear(camera.position_m(), {2.f, 1.f, 0.f}, kTolerance_m);
}

TEST(FlyCamera, DiagonalMoveIsNoFasterThanOneAxisAndZeroStaysPut) {
    FlyCamera camera = FlyCamera::lookingAt({0.f, 0.f, 0.f}, {0.f, 0.f, -1.f});
    camera.move({1.f, 0.f, 1.f}, 1.f);
    EXPECT_NEAR(glm::length(camera.position_m()), 1.f, kTolerance_m) << text(camera.position_m());
    const glm::vec3 before = camera.position_m();
    camera.move({0.f, 0.f, 0.f}, 1.f);
    expectNear(camera.position_m(), before, kTolerance_m);
}

TEST(FlyCamera, MouseRightTurnsRightAndMouseDownLooksDown) {
    constexpr float kTurn_radPerPx = 0.01f;
    FlyCamera camera = FlyCamera::lookingAt({0.f, 0.f, 0.f}, {0.f, 0.f, -1.f});
    camera.look({50.f, 0.f}, kTurn_radPerPx);  // 0.5 rad to the right
    EXPECT_NEAR(camera.yaw_rad(), 0.5f, kTolerance_m);
    EXPECT_GT(camera.forward().x, 0.f) << text(camera.forward());
    EXPECT_NEAR(camera.forward().y, 0.f, kTolerance_m) << text(camera.forward());
    camera.look({0.f, 30.f}, kTurn_radPerPx);  // 0.3 rad down
    EXPECT_NEAR(camera.pitch_rad(), -0.3f, kTolerance_m);
    expectNear(camera.forward(),
               {std::cos(0.3f) * std::sin(0.5f), -std::sin(0.3f), -std::cos(0.3f) * std::cos(0.5f)},
               kTolerance_m);
    // The right vector stays horizontal and perpendicular to the view.
    EXPECT_NEAR(camera.right().y, 0.f, kTolerance_m);
    EXPECT_NEAR(glm::dot(camera.right(), camera.forward()), 0.f, kTolerance_m);
}

TEST(FlyCamera, PitchIsClampedShortOfStraightUpAndDown) {
    FlyCamera camera = FlyCamera::lookingAt({0.f, 0.f, 0.f}, {0.f, 0.f, -1.f});
    camera.look({0.f, -100000.f}, 0.01f);  // far past straight up
    EXPECT_FLOAT_EQ(camera.pitch_rad(), FlyCamera::kMaxPitch_rad);
    EXPECT_LT(camera.forward().y, 0.999f) << "the renderer rolls its up vector beyond this";
    camera.look({0.f, 100000.f}, 0.01f);
    EXPECT_FLOAT_EQ(camera.pitch_rad(), -FlyCamera::kMaxPitch_rad);
    const FlyCamera straightDown = FlyCamera::lookingAt({0.f, 5.f, 0.f}, {0.f, 0.f, 0.f});
    EXPECT_FLOAT_EQ(straightDown.pitch_rad(), -FlyCamera::kMaxPitch_rad);
}

TEST(FlyCamera, CoincidentTargetLooksAlongMinusZ) {
    const FlyCamera camera = FlyCamera::lookingAt({1.f, 1.f, 1.f}, {1.f, 1.f, 1.f});
    expectNear(camera.forward(), {0.f, 0.f, -1.f}, kTolerance_m);
}

}  // namespace
