// The blade-local frame of archetype.h from a spine in camera space.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "meadow/modeling/blade_fit.h"

namespace meadow::modeling {
namespace {

// Below this (relative to the spine's chord) a direction is treated as zero: the spine is
// straight, or v1 sits on v0.
constexpr float kDegenerateFraction = 1e-3f;

}  // namespace

glm::vec3 BladeFrame::toLocal(const glm::vec3& camera_m) const {
    return localFromCamera * (camera_m - origin_m);
}
glm::vec3 BladeFrame::toCamera(const glm::vec3& local_m) const {
    return glm::transpose(localFromCamera) * local_m + origin_m;
}

BladeFrame bladeLocalFrame(const QuadraticBezier& spine, const glm::vec3& acrossHint) {
    const glm::vec3 chord = spine.v2 - spine.v0;
    const float scale = std::max(glm::length(chord), 1e-9f);
    glm::vec3 y = spine.v1 - spine.v0;
    if (glm::length(y) < kDegenerateFraction * scale) y = chord;
    y = glm::length(y) > 0.f ? glm::normalize(y) : glm::vec3(0.f, -1.f, 0.f);  // camera up is -y
    const auto perpendicular = [&](const glm::vec3& v) { return v - glm::dot(v, y) * y; };
    glm::vec3 x = perpendicular(chord);
    if (glm::length(x) < kDegenerateFraction * scale) x = perpendicular(acrossHint);
    if (glm::length(x) < kDegenerateFraction) x = perpendicular(glm::vec3(1.f, 0.f, 0.f));
    if (glm::length(x) < kDegenerateFraction) x = perpendicular(glm::vec3(0.f, 0.f, 1.f));
    x = glm::normalize(x);
    // A nearly straight spine took X from a hint: still point it toward the tip's side.
    if (glm::dot(x, chord) < 0.f) x = -x;
    const glm::vec3 z = glm::cross(x, y);
    BladeFrame frame;
    frame.origin_m = spine.v0;
    // Rows of localFromCamera are the local axes in camera coordinates (glm is column-major).
    frame.localFromCamera = glm::transpose(glm::mat3(x, y, z));
    return frame;
}

}  // namespace meadow::modeling
