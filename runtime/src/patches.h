#pragma once
// Equal-size compact patches of blades (Jahrmann & Wimmer 2017, Sec. 4): the culling pass tests
// a patch's box before its blades, so patches must be spatially tight and all the same size (one
// or more whole workgroups each).
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "shared/blade_types.h"

namespace meadow::runtime {

struct PatchLayout {
    std::vector<std::uint32_t> order;    // order[newIndex] = index of the blade in the input
    std::vector<gpu::PatchGpu> patches;  // blades [range.x, range.x + range.y) of the new order
};

// Balanced clustering by recursive median split along the longest axis of the roots' box, with
// every split at a multiple of patchSize, so each leaf holds exactly patchSize blades; inside a
// patch, blades follow a Morton (Z-order) curve for memory locality. Patches come out in
// depth-first order of the split tree, itself spatially coherent. reach_m[i] is how far blade i
// can get from its root (its height): the boxes include every pose it can reach.
// Preconditions: roots.size() == reach_m.size(), a positive multiple of patchSize.
PatchLayout buildPatches(const std::vector<glm::vec3>& roots_m, const std::vector<float>& reach_m,
                         std::size_t patchSize);

}  // namespace meadow::runtime
