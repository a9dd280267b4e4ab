#include "collider_shapes.h"

#include <cmath>
#include <numbers>

#include "sphere_packing.h"

namespace meadow::runtime {

TriangleMesh sphereMesh(float radius_m, int rings, int segments) {
    TriangleMesh mesh;
    mesh.origin = "sphere collider";
    for (int r = 0; r <= rings; ++r) {
        const float theta = std::numbers::pi_v<float> * static_cast<float>(r) / rings;
        for (int s = 0; s <= segments; ++s) {
            const float phi = 2.f * std::numbers::pi_v<float> * static_cast<float>(s) / segments;
            const glm::vec3 n{std::sin(theta) * std::cos(phi), std::cos(theta),
                              std::sin(theta) * std::sin(phi)};
            mesh.positions_m.push_back(radius_m * n);
            mesh.normals.push_back(n);
        }
    }
    const auto at = [segments](int r, int s) {
        return static_cast<unsigned>(r * (segments + 1) + s);
    };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            if (r > 0) mesh.triangles.emplace_back(at(r, s), at(r, s + 1), at(r + 1, s));
            if (r < rings - 1)
                mesh.triangles.emplace_back(at(r, s + 1), at(r + 1, s + 1), at(r + 1, s));
        }
    return mesh;
}

ColliderShape colliderShape(const ColliderDescription& collider) {
    ColliderShape shape;
    if (!collider.gltf) {
        shape.mesh = sphereMesh(collider.radius_m);
        shape.spheres = {{glm::vec3(0.f), collider.radius_m}};
        return shape;
    }
    shape.mesh = loadGltfTriangles(*collider.gltf);
    const SpherePacking packed = packSpheres(shape.mesh, {.maxSpheres = collider.maxSpheres});
    shape.spheres = packed.spheres;
    shape.coverage = packed.coverage;
    return shape;
}

}  // namespace meadow::runtime
