#include "scene_gpu.h"

#include <numeric>

#include "gl/buffers.h"
#include "ground_maps.h"
#include "meadow/runtime/error.h"
#include "patches.h"
#include "tile_patch.h"
#include "tiled_field.h"

namespace meadow::runtime {
namespace {

using gl::bufferOf;

GpuMesh uploadMesh(const TriangleMesh& mesh, glm::vec3 albedo) {
    std::vector<float> interleaved;
    interleaved.reserve(mesh.positions_m.size() * 6);
    for (std::size_t i = 0; i < mesh.positions_m.size(); ++i)
        for (const glm::vec3& v : {mesh.positions_m[i], mesh.normals[i]})
            interleaved.insert(interleaved.end(), {v.x, v.y, v.z});
    GpuMesh g;
    g.vertices = bufferOf(interleaved, 0);
    g.indices = bufferOf(mesh.triangles, 0);
    g.indexCount = static_cast<GLsizei>(mesh.triangles.size() * 3);
    g.vertexCount = static_cast<GLsizei>(mesh.positions_m.size());
    g.albedo = albedo;
    g.vertexArray = gl::VertexArray::create();
    const GLuint vao = g.vertexArray.id();
    glVertexArrayVertexBuffer(vao, 0, g.vertices.id(), 0, 6 * sizeof(float));
    glVertexArrayElementBuffer(vao, g.indices.id());
    for (GLuint attribute : {0u, 1u}) {
        glEnableVertexArrayAttrib(vao, attribute);
        glVertexArrayAttribFormat(vao, attribute, 3, GL_FLOAT, GL_FALSE,
                                  attribute * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao, attribute, 0);
    }
    return g;
}

}  // namespace

std::size_t patchSizeOf(const SceneDescription& scene) {
    const auto wg = static_cast<std::size_t>(BLADE_WORKGROUP_SIZE);
    return (static_cast<std::size_t>(scene.render.patchSize) + wg - 1) / wg * wg;
}

SceneBlades buildSceneBlades(const SceneDescription& scene) {
    SceneBlades out;
    for (const SceneMesh& m : scene.grassMeshes)
        out.grassMeshes.push_back(loadGltfTriangles(m.gltf));
    for (const SceneMesh& m : scene.props) out.props.push_back(loadGltfTriangles(m.gltf));
    out.patchSize = patchSizeOf(scene);
    for (const ColliderDescription& c : scene.colliders) out.colliders.push_back(colliderShape(c));
    for (const modeling::Archetype& a : scene.archetypes)
        out.archetypes.push_back(archetypeForGpu(a, a.width.width_m.size() > 2));
    if (scene.tiling) {
        out.terrain = makeHeightField(*scene.terrain);
        out.terrainMesh = terrainMesh(*out.terrain);
        try {
            out.tilePatch = buildTilePatch(scene);
        } catch (const RuntimeError& e) {
            throw RuntimeError(scene.file.string() + ": " + e.what());
        }
        return out;
    }

    SeedingInput input;
    input.meshes = &out.grassMeshes;
    input.params = &scene.blades;
    input.archetypes = &scene.archetypes;
    input.archetypeWeights = &scene.archetypeWeights;
    if (scene.blades.densityMap) input.densityMap = loadDensityMap(*scene.blades.densityMap);
    if (scene.archetypeMap) {
        input.archetypeMap = loadArchetypeMap(*scene.archetypeMap, scene.archetypes.size());
        input.archetypeMapExtent = *scene.archetypeMap;
    }
    input.countMultiple = out.patchSize;
    std::vector<SeededBlade> seeds;
    try {
        seeds = seedBlades(input);
    } catch (const RuntimeError& e) {
        throw RuntimeError(scene.file.string() + ": " + e.what());  // which scene asked for it
    }

    std::vector<glm::vec3> roots;
    std::vector<float> reach;
    for (const SeededBlade& s : seeds) {
        roots.push_back(s.root_m);
        reach.push_back(scene.archetypes[s.archetype].height_m() * s.heightScale);
    }
    const PatchLayout layout = buildPatches(roots, reach, out.patchSize);
    out.patches = layout.patches;
    for (std::uint32_t i : layout.order) {
        const SeededBlade& s = seeds[i];
        out.seeds.push_back(s);
        out.blades.push_back(restPose(s, scene.archetypes[s.archetype]));
        out.rests.push_back(restState(s, out.blades.back()));
    }
    return out;
}

SceneGpu uploadScene(const SceneBlades& b, const SceneDescription& scene) {
    SceneGpu g;
    g.patchCount = static_cast<std::uint32_t>(b.patches.size());
    if (scene.tiling) {
        // Filled each frame by the tiles' emit pass.
        g.bladeCount = tiledDrawCapacity(*scene.tiling);
        g.blades = gl::bufferFor<gpu::BladeGpu>(g.bladeCount);
        g.rests = gl::bufferFor<gpu::BladeRestGpu>(g.bladeCount);
    } else {
        g.bladeCount = static_cast<std::uint32_t>(b.blades.size());
        g.blades = bufferOf(b.blades);
        g.rests = bufferOf(b.rests);
    }
    g.archetypes = bufferOf(b.archetypes);
    std::vector<std::uint32_t> all(g.bladeCount);
    std::iota(all.begin(), all.end(), 0u);
    g.visibleIndices = bufferOf(all);
    g.drawCommand = bufferOf(std::vector<gpu::DrawCommandGpu>{{g.bladeCount, 1u, 0u, 0u}});
    g.cullStats = bufferOf(std::vector<gpu::CullStatsGpu>{{0u, 0u, 0u, 0u}});
    g.patches = bufferOf(b.patches);
    g.frame = bufferOf(std::vector<gpu::FrameGpu>(1));
    if (scene.terrain) {
        g.meshes.push_back(uploadMesh(b.terrainMesh, scene.terrain->albedo));
        g.meshes.back().terrain = true;
    }
    for (std::size_t i = 0; i < b.grassMeshes.size(); ++i)
        g.meshes.push_back(uploadMesh(b.grassMeshes[i], scene.grassMeshes[i].albedo));
    for (std::size_t i = 0; i < b.props.size(); ++i)
        g.meshes.push_back(uploadMesh(b.props[i], scene.props[i].albedo));
    g.firstColliderMesh = g.meshes.size();
    for (std::size_t i = 0; i < b.colliders.size() && i < scene.colliders.size(); ++i) {
        g.meshes.push_back(uploadMesh(b.colliders[i].mesh, scene.colliders[i].albedo));
        g.meshes.back().visible = scene.colliders[i].visible;
        g.colliderSpheres.push_back(b.colliders[i].spheres);
    }
    g.placeColliders(scene, 0.f);
    return g;
}

void SceneGpu::bindAll() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_SSBO_BINDING, blades.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_REST_SSBO_BINDING, rests.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, ARCHETYPE_SSBO_BINDING, archetypes.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VISIBLE_INDEX_SSBO_BINDING, visibleIndices.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, DRAW_COMMAND_SSBO_BINDING, drawCommand.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CULL_STATS_SSBO_BINDING, cullStats.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, PATCH_SSBO_BINDING, patches.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, FRAME_UBO_BINDING, frame.id());
}

void SceneGpu::placeColliders(const SceneDescription& scene, float time_s) {
    for (std::size_t i = 0; i < colliderSpheres.size(); ++i)
        meshes[firstColliderMesh + i].offset_m = scene.colliders[i].positionAt(time_s);
}

void SceneGpu::fillTrivialVisibility() const {
    const gpu::DrawCommandGpu all{bladeCount, 1u, 0u, 0u};
    glNamedBufferSubData(drawCommand.id(), 0, sizeof all, &all);
    const gpu::CullStatsGpu none{0u, 0u, 0u, 0u};
    glNamedBufferSubData(cullStats.id(), 0, sizeof none, &none);
}

}  // namespace meadow::runtime
