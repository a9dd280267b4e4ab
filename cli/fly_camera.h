#pragma once
// The camera of `meadow view`: a free-flying position with a heading, yaw about world +Y and pitch
// above the horizon, moved by keys and turned by the mouse. Pure math, no window.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace meadow::cli {

class FlyCamera {
public:
    // Pitch stays within this of the horizon: the renderer switches its up vector when the view
    // is within about 2.6 degrees of straight up or down, which would roll the picture.
    static constexpr float kMaxPitch_rad = 1.48353f;  // 85 degrees

    // At position_m, looking at target_m (straight ahead along -Z when they coincide).
    static FlyCamera lookingAt(glm::vec3 position_m, glm::vec3 target_m);

    [[nodiscard]] glm::vec3 position_m() const { return position_m_; }
    [[nodiscard]] float yaw_rad() const { return yaw_rad_; }      // 0 looks along -Z, + turns right
    [[nodiscard]] float pitch_rad() const { return pitch_rad_; }  // + looks up
    [[nodiscard]] glm::vec3 forward() const;                      // unit view direction
    [[nodiscard]] glm::vec3 right() const;  // unit, horizontal, to the right of the view
    // A point one metre ahead, for the renderer's position/target pose.
    [[nodiscard]] glm::vec3 target_m() const { return position_m_ + forward(); }

    // Flies distance_m toward rightUpForward: x along right(), y along world +Y, z along
    // forward(). Diagonals are no faster than one axis; a zero direction stays put.
    void move(glm::vec3 rightUpForward, float distance_m);
    // Turns by a cursor movement in pixels: +x turns right, +y (down the screen) looks down.
    void look(glm::vec2 cursorDelta_px, float turn_radPerPx);

private:
    FlyCamera(glm::vec3 position_m, float yaw_rad, float pitch_rad);
    glm::vec3 position_m_;
    float yaw_rad_, pitch_rad_;
};

}  // namespace meadow::cli
