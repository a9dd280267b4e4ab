#pragma once
// Points as small discs (splats), so that a scan sparser than a camera's pixels renders as a
// closed surface: each point becomes a hexagon in the plane of its normal (PCL's normal
// estimation over its nearest neighbours) reaching as far as the farthest of those neighbours.
#include <glm/vec3.hpp>
#include <vector>

#include "meadow/modeling/blade_mesh.h"

namespace meadow::synth::plant {

struct SplatParams {
    int neighbours = 8;               // for the normal and the local spacing
    float radiusScale = 1.15f;        // radius = this x the distance to the farthest neighbour
    float maxRadiusOverMedian = 3.f;  // no splat larger than this x the median splat
    int sides = 6;
};

// One triangle mesh of splats over `points` (world), normals filled in. Throws SynthError for
// fewer points than neighbours + 1.
modeling::TriangleMesh splatMesh(const std::vector<glm::vec3>& points,
                                 const SplatParams& params = {});

}  // namespace meadow::synth::plant
