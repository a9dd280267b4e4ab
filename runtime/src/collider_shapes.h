#pragma once
// Colliders as the renderer needs them: a mesh to draw and the spheres that push blades, both
// relative to the collider's position (ColliderDescription::positionAt).
#include <vector>

#include "meadow/runtime/physics.h"
#include "meadow/runtime/scene.h"
#include "scene_mesh.h"

namespace meadow::runtime {

struct ColliderShape {
    TriangleMesh mesh;
    std::vector<CollisionSphere> spheres;
    float coverage = 1.f;  // share of the mesh's volume the spheres cover
};

// A sphere collider: a UV sphere of its radius and one sphere. A mesh collider: its glTF mesh and
// the spheres packed into it (sphere_packing.h). Throws RuntimeError naming the file.
ColliderShape colliderShape(const ColliderDescription& collider);

// A UV sphere about the origin: `rings` bands of latitude, `segments` of longitude.
TriangleMesh sphereMesh(float radius_m, int rings = 12, int segments = 24);

}  // namespace meadow::runtime
