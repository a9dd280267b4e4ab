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

// Appends the quad a-b-c-d (in order around its border) as two triangles.
void addQuad(LabelledMesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d);
// A closed axis-aligned box between corners lo and hi (metres), six quads.
[[nodiscard]] LabelledMesh boxMesh(glm::vec3 lo, glm::vec3 hi, std::uint16_t label);

// The blade-local mesh placed in camera space by a rigid cameraFromBlade and labelled.
[[nodiscard]] LabelledMesh placeBlade(const modeling::TriangleMesh& bladeLocal,
                                      const glm::mat4& cameraFromBlade, std::uint16_t label);
[[nodiscard]] LabelledMesh placeBlade(const modeling::Archetype& archetype,
                                      const glm::mat4& cameraFromBlade, std::uint16_t label,
                                      const modeling::BladeMeshOptions& options = {});

}  // namespace meadow::synth
