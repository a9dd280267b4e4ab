#pragma once
// A scene as the GPU passes see it: the blade buffers at the bindings of blade_types.h, the
// opaque meshes, and the CPU-side arrays they were filled from (kept for tests and the CPU
// reference). Built once per scene; the passes read and write the buffers every frame.
#include <cstdint>
#include <optional>
#include <vector>

#include "collider_shapes.h"
#include "gl/gl_object.h"
#include "meadow/runtime/scene.h"
#include "scene_mesh.h"
#include "seeding.h"
#include "shared/blade_types.h"
#include "shared/tiling_types.h"
#include "terrain.h"

namespace meadow::runtime {

class GlContext;

// The CPU half: seeded, patch-ordered blades. Needs no GL context.
struct SceneBlades {
    std::vector<TriangleMesh> grassMeshes;
    std::vector<TriangleMesh> props;
    std::vector<SeededBlade> seeds;  // in patch order
    std::vector<gpu::BladeGpu> blades;
    std::vector<gpu::BladeRestGpu> rests;
    std::vector<gpu::ArchetypeGpu> archetypes;
    std::vector<gpu::PatchGpu> patches;
    std::size_t patchSize = 0;
    std::vector<ColliderShape> colliders;  // one per scene collider, in its order
    // A tiled scene (scene.tiling): the terrain and the patch every tile draws; no stored blades.
    std::optional<HeightField> terrain;
    TriangleMesh terrainMesh;
    std::vector<gpu::TileInstanceGpu> tilePatch;
};

// The patch size of the scene rounded up to whole workgroups.
std::size_t patchSizeOf(const SceneDescription& scene);
// Loads the meshes, density and archetype maps, seeds, orders into patches. Throws RuntimeError.
SceneBlades buildSceneBlades(const SceneDescription& scene);

struct GpuMesh {
    gl::Buffer vertices;  // interleaved position (m) and normal, 6 floats
    gl::Buffer indices;   // uint32 triangles
    gl::VertexArray vertexArray;
    GLsizei indexCount = 0;
    GLsizei vertexCount = 0;
    glm::vec3 albedo{0.f};
    glm::vec3 offset_m{0.f};  // added to every vertex: where a collider has moved
    bool visible = true;      // a hidden collider still pushes blades, it is not drawn
    bool terrain = false;     // a tiled scene's ground: shaded with the far field
};

struct SceneGpu {
    // Stored blades; for a tiled scene the room for the blades emitted each frame.
    std::uint32_t bladeCount = 0;
    std::uint32_t patchCount = 0;
    gl::Buffer blades;          // BladeGpu[bladeCount]            BLADE_SSBO_BINDING
    gl::Buffer rests;           // BladeRestGpu[bladeCount]        BLADE_REST_SSBO_BINDING
    gl::Buffer archetypes;      // ArchetypeGpu[]                  ARCHETYPE_SSBO_BINDING
    gl::Buffer visibleIndices;  // uint[bladeCount]                VISIBLE_INDEX_SSBO_BINDING
    gl::Buffer drawCommand;  // DrawCommandGpu                  DRAW_COMMAND_SSBO_BINDING + indirect
    gl::Buffer cullStats;    // CullStatsGpu                    CULL_STATS_SSBO_BINDING
    gl::Buffer patches;      // PatchGpu[patchCount]            PATCH_SSBO_BINDING
    gl::Buffer frame;        // FrameGpu                        FRAME_UBO_BINDING
    std::vector<GpuMesh> meshes;  // terrain or grass ground first, then props, then colliders
    std::size_t firstColliderMesh = 0;
    // Each collider's spheres relative to its position (ColliderDescription::positionAt).
    std::vector<std::vector<CollisionSphere>> colliderSpheres;

    // Moves the colliders' meshes to where the scene's colliders are at time_s.
    void placeColliders(const SceneDescription& scene, float time_s);

    // Binds every buffer at its binding point (each pass may rely on this after the call).
    void bindAll() const;
    // Until a culling pass exists: every blade visible, the draw command draws all of them.
    void fillTrivialVisibility() const;
};

SceneGpu uploadScene(const SceneBlades& blades, const SceneDescription& scene);

}  // namespace meadow::runtime
