#pragma once
// A closed triangle mesh as spheres, for collisions (Jahrmann & Wimmer 2017, Sec. 5.1: any
// collider is approximated by spheres, which the blade test handles in closed form). The mesh is
// voxelised, each inside voxel gets its distance to the outside (Felzenszwalb & Huttenlocher's
// separable Euclidean distance transform), and spheres are placed greedily: the deepest voxel
// not yet covered becomes the centre of a sphere reaching to the surface, until the spheres
// cover the volume or the count runs out.
#include <vector>

#include "meadow/runtime/physics.h"
#include "scene_mesh.h"

namespace meadow::runtime {

struct SpherePackingParams {
    int resolution = 32;     // voxels along the mesh's longest side
    int maxSpheres = 32;     // at most this many spheres
    float coverage = 0.97f;  // stop once this share of the inside voxels is covered
};

struct SpherePacking {
    std::vector<CollisionSphere> spheres;  // in the mesh's coordinates, largest first
    float coverage = 0.f;  // share of the inside voxels within half a voxel of some sphere
    float voxel_m = 0.f;   // the voxel size used
};

// Throws RuntimeError naming the mesh's file when it encloses no volume (an open surface, a
// plane) at this resolution.
SpherePacking packSpheres(const TriangleMesh& mesh, const SpherePackingParams& params = {});

}  // namespace meadow::runtime
