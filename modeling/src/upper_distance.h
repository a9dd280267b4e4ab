#pragma once
// How far apart two blades' polylines lie, as blade tracking (blade_tracks.cpp) and joining a
// turning plant's views (view_joining.cpp) tell one blade from two.
#include <glm/vec3.hpp>
#include <limits>
#include <vector>

namespace meadow::modeling::detail {

// Mean distance of the shorter polyline's upper three quarters to the longer polyline (lengths
// given, as the caller has them), or +inf as soon as that mean must exceed limit_m (most pairs are
// two different blades, far apart). Both run root to tip. +inf for fewer than 2 points.
float upperDistance_m(const std::vector<glm::vec3>& a, float lengthA_m,
                      const std::vector<glm::vec3>& b, float lengthB_m,
                      float limit_m = std::numeric_limits<float>::infinity());

}  // namespace meadow::modeling::detail
