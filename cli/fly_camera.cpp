#include "fly_camera.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace meadow::cli {

FlyCamera::FlyCamera(glm::vec3 position_m, float yaw_rad, float pitch_rad)
    : position_m_(position_m),
      yaw_rad_(yaw_rad),
      pitch_rad_(std::clamp(pitch_rad, -kMaxPitch_rad, kMaxPitch_rad)) {}

FlyCamera FlyCamera::lookingAt(glm::vec3 position_m, glm::vec3 target_m) {
    const glm::vec3 d = target_m - position_m;
    const float horizontal_m = std::hypot(d.x, d.z);
    if (horizontal_m == 0.f && d.y == 0.f) return {position_m, 0.f, 0.f};
    // forward() inverted: x = cos(pitch) sin(yaw), z = -cos(pitch) cos(yaw).
    const float yaw_rad = horizontal_m > 0.f ? std::atan2(d.x, -d.z) : 0.f;
    return {position_m, yaw_rad, std::atan2(d.y, horizontal_m)};
}

glm::vec3 FlyCamera::forward() const {
    const float c = std::cos(pitch_rad_);
    return {c * std::sin(yaw_rad_), std::sin(pitch_rad_), -c * std::cos(yaw_rad_)};
}

glm::vec3 FlyCamera::right() const { return {std::cos(yaw_rad_), 0.f, std::sin(yaw_rad_)}; }

void FlyCamera::move(glm::vec3 rightUpForward, float distance_m) {
    const glm::vec3 d = rightUpForward.x * right() + rightUpForward.y * glm::vec3(0.f, 1.f, 0.f) +
                        rightUpForward.z * forward();
    const float length = glm::length(d);
    if (length > 0.f) position_m_ += d * (distance_m / length);
}

void FlyCamera::look(glm::vec2 cursorDelta_px, float turn_radPerPx) {
    constexpr float kTwoPi = 6.28318531f;
    yaw_rad_ = std::remainder(yaw_rad_ + cursorDelta_px.x * turn_radPerPx, kTwoPi);
    pitch_rad_ =
        std::clamp(pitch_rad_ - cursorDelta_px.y * turn_radPerPx, -kMaxPitch_rad, kMaxPitch_rad);
}

}  // namespace meadow::cli
