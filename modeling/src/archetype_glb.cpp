#include "meadow/modeling/archetype_glb.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "archetype_json.h"
#include "meadow/core/atomic_file.h"
#include "meadow/modeling/blade_mesh.h"
#include "meadow/modeling/error.h"

namespace meadow::modeling {

namespace {

// glTF requires accessor offsets aligned to their component size; 4 bytes covers float and uint.
constexpr std::size_t kBufferAlignment = 4;
constexpr double kBladeGreen[4] = {0.30, 0.55, 0.18, 1.0};

tinygltf::Value toGltfValue(const nlohmann::json& j) {
    switch (j.type()) {
        case nlohmann::json::value_t::boolean:
            return tinygltf::Value(j.get<bool>());
        case nlohmann::json::value_t::number_integer:
        case nlohmann::json::value_t::number_unsigned:
            return tinygltf::Value(j.get<int>());
        case nlohmann::json::value_t::number_float:
            return tinygltf::Value(j.get<double>());
        case nlohmann::json::value_t::string:
            return tinygltf::Value(j.get<std::string>());
        case nlohmann::json::value_t::array: {
            tinygltf::Value::Array a;
            for (const auto& e : j) a.push_back(toGltfValue(e));
            return tinygltf::Value(std::move(a));
        }
        case nlohmann::json::value_t::object: {
            tinygltf::Value::Object o;
            for (const auto& [k, v] : j.items()) o[k] = toGltfValue(v);
            return tinygltf::Value(std::move(o));
        }
        default:
            return tinygltf::Value();
    }
}

// Appends raw data to the single buffer and returns the index of a new buffer view over it.
int appendView(tinygltf::Model& model, const void* data, std::size_t bytes, int target) {
    auto& buffer = model.buffers[0].data;
    buffer.resize((buffer.size() + kBufferAlignment - 1) / kBufferAlignment * kBufferAlignment);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.insert(buffer.end(), p, p + bytes);
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size() - 1);
}

int appendVec3Accessor(tinygltf::Model& model, const std::vector<glm::vec3>& values,
                       bool withBounds) {
    tinygltf::Accessor acc;
    acc.bufferView = appendView(model, values.data(), values.size() * sizeof(glm::vec3),
                                TINYGLTF_TARGET_ARRAY_BUFFER);
    acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    acc.type = TINYGLTF_TYPE_VEC3;
    acc.count = values.size();
    if (withBounds) {  // POSITION accessors must carry min and max (glTF 2.0, 3.6.2.1)
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (const auto& v : values) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        acc.minValues = {lo.x, lo.y, lo.z};
        acc.maxValues = {hi.x, hi.y, hi.z};
    }
    model.accessors.push_back(acc);
    return static_cast<int>(model.accessors.size() - 1);
}

int appendIndexAccessor(tinygltf::Model& model, const std::vector<glm::uvec3>& triangles) {
    tinygltf::Accessor acc;
    acc.bufferView = appendView(model, triangles.data(), triangles.size() * sizeof(glm::uvec3),
                                TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    acc.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    acc.type = TINYGLTF_TYPE_SCALAR;
    acc.count = triangles.size() * 3;
    model.accessors.push_back(acc);
    return static_cast<int>(model.accessors.size() - 1);
}

}  // namespace

std::string archetypeGlbBytes(const ArchetypeLibrary& library, const GlbExportOptions& options) {
    if (library.archetypes.empty())
        throw ModelingError("cannot export an archetype library with no archetypes");
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = library.generator.empty() ? "meadow" : library.generator;
    model.buffers.emplace_back();

    tinygltf::Material blade;
    blade.name = "blade";
    blade.doubleSided = true;  // a blade is a ribbon: both faces are seen
    blade.pbrMetallicRoughness.baseColorFactor.assign(std::begin(kBladeGreen),
                                                      std::end(kBladeGreen));
    blade.pbrMetallicRoughness.metallicFactor = 0.0;
    blade.pbrMetallicRoughness.roughnessFactor = 0.8;
    model.materials.push_back(blade);

    std::vector<TriangleMesh> meshes;
    float widest_m = 0.f;
    for (const Archetype& a : library.archetypes) {
        meshes.push_back(bladeMesh(a, {.segments = options.segmentsPerBlade}));
        float lo = 0.f, hi = 0.f;
        for (const auto& p : meshes.back().positions_m) {
            lo = std::min(lo, p.x);
            hi = std::max(hi, p.x);
        }
        widest_m = std::max({widest_m, hi - lo, a.height_m() * 0.25f});
    }
    const float spacing_m = options.nodeSpacing_m > 0.f ? options.nodeSpacing_m : 1.5f * widest_m;

    tinygltf::Scene scene;
    scene.name = "archetypes";
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const Archetype& a = library.archetypes[i];
        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        prim.material = 0;
        prim.attributes["POSITION"] = appendVec3Accessor(model, meshes[i].positions_m, true);
        prim.attributes["NORMAL"] = appendVec3Accessor(model, meshes[i].normals, false);
        prim.indices = appendIndexAccessor(model, meshes[i].triangles);
        tinygltf::Mesh mesh;
        mesh.name = a.name;
        mesh.primitives.push_back(prim);
        model.meshes.push_back(mesh);

        tinygltf::Node node;
        node.name = a.name;
        node.mesh = static_cast<int>(i);
        node.translation = {static_cast<double>(i) * spacing_m, 0.0, 0.0};
        node.extras = toGltfValue(detail::archetypeToJson(a));
        model.nodes.push_back(node);
        scene.nodes.push_back(static_cast<int>(i));
    }
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    model.buffers[0].data.resize((model.buffers[0].data.size() + 3) / 4 * 4);

    std::ostringstream out;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/false, /*writeBinary=*/true))
        throw ModelingError("tinygltf could not serialise the archetype library");
    return out.str();
}

void exportArchetypeGlb(const ArchetypeLibrary& library, const std::filesystem::path& glbPath,
                        const GlbExportOptions& options) {
    writeFileAtomically(glbPath, archetypeGlbBytes(library, options));
}

bool isMeadowGlb(const std::filesystem::path& path) {
    // The 12-byte header, the JSON chunk's header, then the JSON: its asset block comes first
    // in what tinygltf writes, so the generator lies within the first few hundred bytes.
    constexpr std::size_t kLookedAt = 4096;
    std::ifstream in(path, std::ios::binary);
    std::string head(kLookedAt, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
    return head.rfind("glTF", 0) == 0 && head.find("\"generator\":\"meadow") != std::string::npos;
}

}  // namespace meadow::modeling
