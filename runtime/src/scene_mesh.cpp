#include "scene_mesh.h"

#include <tiny_gltf.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>

#include "meadow/core/library_messages.h"
#include "meadow/runtime/error.h"

namespace meadow::runtime {
namespace {

constexpr int kGltfModeTriangles = 4;  // glTF 2.0 primitive.mode TRIANGLES (the default)

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
    throw RuntimeError(file.string() + ": " + what);
}

glm::mat4 localFromNode(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::mat4 m;
        for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = static_cast<float>(node.matrix[i]);
        return m;  // glTF matrices are column-major, like glm
    }
    glm::mat4 m(1.f);
    if (node.translation.size() == 3)
        m[3] = glm::vec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    if (node.rotation.size() == 4) {
        const glm::quat q(
            static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
            static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
        m = m * glm::mat4_cast(q);
    }
    if (node.scale.size() == 3)
        m = m * glm::mat4(glm::vec4(node.scale[0], 0, 0, 0), glm::vec4(0, node.scale[1], 0, 0),
                          glm::vec4(0, 0, node.scale[2], 0), glm::vec4(0, 0, 0, 1));
    return m;
}

// The float VEC3 elements of an accessor.
std::vector<glm::vec3> readVec3(const tinygltf::Model& model, int accessorIndex,
                                const std::filesystem::path& file) {
    const tinygltf::Accessor& a = model.accessors.at(static_cast<std::size_t>(accessorIndex));
    if (a.type != TINYGLTF_TYPE_VEC3 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT ||
        a.sparse.isSparse)
        fail(file, "accessor " + std::to_string(accessorIndex) + " is not a dense float VEC3");
    if (a.bufferView < 0)
        fail(file, "accessor " + std::to_string(accessorIndex) + " has no buffer view");
    const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(a.bufferView));
    const tinygltf::Buffer& buffer = model.buffers.at(static_cast<std::size_t>(view.buffer));
    const std::size_t stride = view.byteStride ? view.byteStride : sizeof(float) * 3;
    const std::size_t begin = view.byteOffset + a.byteOffset;
    if (a.count > 0 && begin + stride * (a.count - 1) + sizeof(float) * 3 > buffer.data.size())
        fail(file, "accessor " + std::to_string(accessorIndex) + " reads past its buffer");
    std::vector<glm::vec3> out(a.count);
    for (std::size_t i = 0; i < a.count; ++i)
        std::memcpy(&out[i], buffer.data.data() + begin + i * stride, sizeof(glm::vec3));
    return out;
}

std::vector<std::uint32_t> readIndices(const tinygltf::Model& model, int accessorIndex,
                                       const std::filesystem::path& file) {
    const tinygltf::Accessor& a = model.accessors.at(static_cast<std::size_t>(accessorIndex));
    if (a.type != TINYGLTF_TYPE_SCALAR || a.bufferView < 0 || a.sparse.isSparse)
        fail(file, "index accessor " + std::to_string(accessorIndex) + " is not a dense scalar");
    const tinygltf::BufferView& view = model.bufferViews.at(static_cast<std::size_t>(a.bufferView));
    const tinygltf::Buffer& buffer = model.buffers.at(static_cast<std::size_t>(view.buffer));
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    if (size != 1 && size != 2 && size != 4) fail(file, "index component type not supported");
    const std::size_t stride = view.byteStride ? view.byteStride : static_cast<std::size_t>(size);
    const std::size_t begin = view.byteOffset + a.byteOffset;
    if (a.count > 0 &&
        begin + stride * (a.count - 1) + static_cast<std::size_t>(size) > buffer.data.size())
        fail(file, "index accessor " + std::to_string(accessorIndex) + " reads past its buffer");
    std::vector<std::uint32_t> out(a.count);
    for (std::size_t i = 0; i < a.count; ++i) {
        const unsigned char* p = buffer.data.data() + begin + i * stride;
        if (size == 1)
            out[i] = *p;
        else if (size == 2) {
            std::uint16_t v;
            std::memcpy(&v, p, 2);
            out[i] = v;
        } else
            std::memcpy(&out[i], p, 4);
    }
    return out;
}

void appendNode(const tinygltf::Model& model, int nodeIndex, const glm::mat4& worldFromParent,
                TriangleMesh& mesh, const std::filesystem::path& file, int depth) {
    constexpr int kMaxNodeDepth = 64;  // deeper than this is a cycle in a malformed file
    if (depth > kMaxNodeDepth) fail(file, "node hierarchy deeper than 64 (a cycle?)");
    const tinygltf::Node& node = model.nodes.at(static_cast<std::size_t>(nodeIndex));
    const glm::mat4 worldFromNode = worldFromParent * localFromNode(node);
    const glm::mat3 normalFromNode = glm::inverseTranspose(glm::mat3(worldFromNode));
    if (node.mesh >= 0) {
        for (const tinygltf::Primitive& prim :
             model.meshes.at(static_cast<std::size_t>(node.mesh)).primitives) {
            if (prim.mode != kGltfModeTriangles && prim.mode != -1)
                fail(file, "primitive mode " + std::to_string(prim.mode) +
                               " is not supported (export triangles, glTF mode 4)");
            const auto position = prim.attributes.find("POSITION");
            if (position == prim.attributes.end()) fail(file, "a primitive has no POSITION");
            const std::vector<glm::vec3> positions = readVec3(model, position->second, file);
            std::vector<glm::vec3> normals;
            if (auto n = prim.attributes.find("NORMAL"); n != prim.attributes.end())
                normals = readVec3(model, n->second, file);
            std::vector<std::uint32_t> indices;
            if (prim.indices >= 0)
                indices = readIndices(model, prim.indices, file);
            else
                for (std::uint32_t i = 0; i < positions.size(); ++i) indices.push_back(i);
            if (indices.size() % 3) fail(file, "triangle index count is not a multiple of 3");
            const auto base = static_cast<std::uint32_t>(mesh.positions_m.size());
            for (std::size_t i = 0; i < positions.size(); ++i) {
                mesh.positions_m.push_back(glm::vec3(worldFromNode * glm::vec4(positions[i], 1.f)));
                mesh.normals.push_back(normals.size() == positions.size()
                                           ? glm::normalize(normalFromNode * normals[i])
                                           : glm::vec3(0.f));  // computed below
            }
            for (std::size_t i = 0; i < indices.size(); i += 3) {
                for (int k = 0; k < 3; ++k)
                    if (indices[i + k] >= positions.size())
                        fail(file, "a triangle index is out of range");
                mesh.triangles.emplace_back(base + indices[i], base + indices[i + 1],
                                            base + indices[i + 2]);
            }
        }
    }
    for (int child : node.children) appendNode(model, child, worldFromNode, mesh, file, depth + 1);
}

TriangleMesh trianglesOf(const tinygltf::Model& model, const std::filesystem::path& file) {
    TriangleMesh mesh;
    mesh.origin = file.string();
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (model.scenes.empty()) {
        for (std::size_t n = 0; n < model.nodes.size(); ++n)
            appendNode(model, static_cast<int>(n), glm::mat4(1.f), mesh, file, 0);
    } else {
        for (int n : model.scenes.at(static_cast<std::size_t>(sceneIndex)).nodes)
            appendNode(model, n, glm::mat4(1.f), mesh, file, 0);
    }
    if (mesh.triangles.empty()) fail(file, "holds no triangles");
    // A mesh in other units (millimetres, or garbage) would plant a meadow kilometres wide.
    constexpr float kMaxExtent_m = 1e5f;
    for (const glm::vec3& p : mesh.positions_m)
        if (!(std::abs(p.x) <= kMaxExtent_m && std::abs(p.y) <= kMaxExtent_m &&
              std::abs(p.z) <= kMaxExtent_m))
            fail(file, "has a vertex " + std::to_string(glm::length(p)) +
                           " m from the origin, beyond 1e5 m: glTF positions are in metres");
    // Area-weighted vertex normals where the file gave none (the cross product's length is twice
    // the area, so summing unnormalised face normals weights by area).
    std::vector<glm::vec3> computed(mesh.positions_m.size(), glm::vec3(0.f));
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 n = glm::cross(mesh.positions_m[t.y] - mesh.positions_m[t.x],
                                       mesh.positions_m[t.z] - mesh.positions_m[t.x]);
        for (int k = 0; k < 3; ++k) computed[t[k]] += n;
    }
    for (std::size_t i = 0; i < mesh.normals.size(); ++i)
        if (glm::dot(mesh.normals[i], mesh.normals[i]) == 0.f)
            mesh.normals[i] = glm::dot(computed[i], computed[i]) > 0.f ? glm::normalize(computed[i])
                                                                       : glm::vec3(0.f, 1.f, 0.f);
    return mesh;
}

}  // namespace

TriangleMesh loadGltfTriangles(const std::filesystem::path& file) {
    if (!std::filesystem::exists(file)) fail(file, "no such file; check the path in the scene");
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string error, warning;
    const bool binary = file.extension() == ".glb";
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, file.string())
                           : loader.LoadASCIIFromFile(&model, &error, &warning, file.string());
    if (!ok) fail(file, "not a readable glTF 2.0 file (" + oneLine(error) + ")");
    return trianglesOf(model, file);
}

TriangleMesh glbTriangles(const std::string& bytes, const std::filesystem::path& file) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string error, warning;
    if (!loader.LoadBinaryFromMemory(&model, &error, &warning,
                                     reinterpret_cast<const unsigned char*>(bytes.data()),
                                     static_cast<unsigned int>(bytes.size())))
        fail(file, "not a readable glTF 2.0 binary (" + oneLine(error) + ")");
    return trianglesOf(model, file);
}

float triangleArea_m2(const TriangleMesh& mesh, std::size_t triangle) {
    const glm::uvec3 t = mesh.triangles[triangle];
    return 0.5f * glm::length(glm::cross(mesh.positions_m[t.y] - mesh.positions_m[t.x],
                                         mesh.positions_m[t.z] - mesh.positions_m[t.x]));
}

float surfaceArea_m2(const TriangleMesh& mesh) {
    double sum = 0.0;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) sum += triangleArea_m2(mesh, i);
    return static_cast<float>(sum);
}

}  // namespace meadow::runtime
