#pragma once
// What the simulated sensor renders: an indexed triangle mesh in camera space (metres) with one
// label for all its pixels, written into the label image (0 = background, not a blade).
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "meadow/modeling/blade_mesh.h"

namespace meadow::synth {

struct LabelledMesh {
    std::vector<glm::vec3> positions_m;
    std::vector<glm::uvec3> triangles;
    std::uint16_t label = 0;
};

// The blade-local mesh placed in camera space by a rigid cameraFromBlade and labelled.
[[nodiscard]] LabelledMesh placeBlade(const modeling::TriangleMesh& bladeLocal,
                                      const glm::mat4& cameraFromBlade, std::uint16_t label);
[[nodiscard]] LabelledMesh placeBlade(const modeling::Archetype& archetype,
                                      const glm::mat4& cameraFromBlade, std::uint16_t label,
                                      const modeling::BladeMeshOptions& options = {});

}  // namespace meadow::synth
