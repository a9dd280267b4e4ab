#include <algorithm>
#include <cmath>

#include "meadow/modeling/archetype.h"

namespace meadow::modeling {

float WidthProfile::at(float s) const {
    if (width_m.empty()) return 0.f;
    if (width_m.size() == 1) return width_m.front();
    const float x = std::clamp(s, 0.f, 1.f) * static_cast<float>(width_m.size() - 1);
    const std::size_t i = std::min(static_cast<std::size_t>(x), width_m.size() - 2);
    const float f = x - static_cast<float>(i);
    return width_m[i] * (1.f - f) + width_m[i + 1] * f;
}

float WidthProfile::maxWidth_m() const {
    return width_m.empty() ? 0.f : *std::max_element(width_m.begin(), width_m.end());
}

}  // namespace meadow::modeling
