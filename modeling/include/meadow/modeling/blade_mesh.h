#pragma once
// Archetype -> triangle mesh: a ribbon along the spine, the one geometry behind the glTF export
// and the simulated sensor's ground truth.
//
// The ribbon has `segments` quads between segments + 1 rings placed at equal arc-length
// fractions s_i = i / segments of the spine. Ring i holds two vertices, left then right:
//   left_i  = B(t_i) - W_i * leftWidthFraction        * width(s_i)
//   right_i = B(t_i) + W_i * (1 - leftWidthFraction) * width(s_i)
// (the archetype's leftWidthFraction)
// where B is the spine, t_i the Bézier parameter of s_i and W_i the unit width direction: in the
// face plane (archetype.h), perpendicular to the spine tangent T_i, i.e. W = normalize(T x Z),
// which is +X for a straight blade (the side it bends toward), then rotated about T_i by the
// twist at s_i (the archetype's twistAtTip_rad times s_i). Vertex normals are normalize(W x T): +Z
// (the archetype's face normal) for a flat blade. Triangles wind counter-clockwise seen from the
// normal's side. Triangles of zero area (at a zero-width tip or base) are left out.
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "meadow/modeling/archetype.h"

namespace meadow::modeling {

// A plain indexed triangle mesh: positions (m), unit per-vertex normals, triangle indices.
struct TriangleMesh {
    std::vector<glm::vec3> positions_m;
    std::vector<glm::vec3> normals;  // one per position, unit length
    std::vector<glm::uvec3> triangles;

    [[nodiscard]] float surfaceArea_m2() const;
};

struct BladeMeshOptions {
    // Quads along the spine; each spans the same arc length. More follow the bend and the width
    // profile more closely (the profile is linear between its samples, so a multiple of its
    // sample count - 1 reproduces it exactly).
    int segments = 16;
};

// The archetype's ribbon in its blade-local frame. Throws std::invalid_argument on
// segments < 1, an archetype leftWidthFraction outside [0, 1], or a spine of zero length.
[[nodiscard]] TriangleMesh bladeMesh(const Archetype& archetype,
                                     const BladeMeshOptions& options = {});

// The mesh moved by a rigid transform (rotation + translation): positions by the full matrix,
// normals by its rotation part.
[[nodiscard]] TriangleMesh transformed(const TriangleMesh& mesh, const glm::mat4& targetFromSource);

}  // namespace meadow::modeling
