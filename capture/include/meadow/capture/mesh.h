#pragma once
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace meadow::capture {

// An indexed triangle mesh in camera space (metres) with one label for all its pixels:
// the simulated sensor writes it into the label image (0 = background, not a blade).
struct LabelledMesh {
    std::vector<glm::vec3> positions_m;
    std::vector<glm::uvec3> triangles;
    std::uint16_t label = 0;
};

}  // namespace meadow::capture
