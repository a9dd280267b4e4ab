#pragma once
// Triangle meshes of a scene, read from glTF 2.0 (any topology, not a height map).
#include <filesystem>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace meadow::runtime {

struct TriangleMesh {
    std::vector<glm::vec3> positions_m;  // world
    std::vector<glm::vec3> normals;      // world, unit, one per position
    std::vector<glm::uvec3> triangles;
    std::string origin;  // file it came from, for messages
};

// Every triangle primitive of the file's default scene (all nodes' transforms applied, so the
// result is in world space). Missing normals are computed (area-weighted). Throws RuntimeError
// naming the file for unreadable files and unsupported primitives.
TriangleMesh loadGltfTriangles(const std::filesystem::path& gltf);
// The same for a .glb's bytes already read; `file` names it in messages.
TriangleMesh glbTriangles(const std::string& bytes, const std::filesystem::path& file);

[[nodiscard]] float triangleArea_m2(const TriangleMesh& mesh, std::size_t triangle);
[[nodiscard]] float surfaceArea_m2(const TriangleMesh& mesh);

}  // namespace meadow::runtime
