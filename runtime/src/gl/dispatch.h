#pragma once
// glDispatchCompute for any number of work groups: GL guarantees 65535 groups a dimension, so
// more are spread over y as well (x * y >= groups). Shaders read their flat index from
// shaders/common_dispatch.glsl and return when it lies past the end.
#include <cstdint>

#include "gl/gl_api.h"

namespace meadow::runtime::gl {

inline constexpr std::uint32_t kMaxGroupsPerDimension = 65535;

inline void dispatchGroups(std::uint32_t groups) {
    if (groups == 0) return;
    const std::uint32_t x = groups < kMaxGroupsPerDimension ? groups : kMaxGroupsPerDimension;
    const std::uint32_t y = (groups + x - 1) / x;
    glDispatchCompute(x, y, 1);
}

}  // namespace meadow::runtime::gl
