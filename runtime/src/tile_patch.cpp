#include "tile_patch.h"

#include <algorithm>
#include <glm/geometric.hpp>

#include "meadow/core/random.h"
#include "seeding.h"

namespace meadow::runtime {

std::vector<gpu::TileInstanceGpu> buildTilePatch(const SceneDescription& scene) {
    const float size = scene.tiling->tileSize_m;
    TriangleMesh tile;
    tile.origin = "tile";
    tile.positions_m = {{0.f, 0.f, 0.f}, {size, 0.f, 0.f}, {size, 0.f, size}, {0.f, 0.f, size}};
    tile.normals.assign(4, glm::vec3(0.f, 1.f, 0.f));
    tile.triangles = {{0u, 2u, 1u}, {0u, 3u, 2u}};
    const std::vector<TriangleMesh> meshes{tile};

    BladeSeeding params = scene.blades;
    params.densityMap.reset();  // thinned per tile at run time, by threshold
    SeedingInput input;
    input.meshes = &meshes;
    input.params = &params;
    input.archetypes = &scene.archetypes;
    input.archetypeWeights = &scene.archetypeWeights;
    input.countMultiple = BLADE_WORKGROUP_SIZE;
    const std::vector<SeededBlade> seeds = seedBlades(input);

    Rng thresholds(scene.blades.seed ^ 0x7468726573686f6cull);
    std::vector<gpu::TileInstanceGpu> patch;
    patch.reserve(seeds.size());
    for (SeededBlade s : seeds) {
        // Roots may stray past the edge with their tuft; the tile wraps them back in.
        s.root_m.x = s.root_m.x - size * std::floor(s.root_m.x / size);
        s.root_m.z = s.root_m.z - size * std::floor(s.root_m.z / size);
        const gpu::BladeGpu pose = restPose(s, scene.archetypes[s.archetype]);
        const glm::vec3 up = s.up;
        const glm::vec3 w = bladeWidthDirection(up, s.directionAngle_rad);
        const glm::vec3 d = glm::cross(w, up);
        const glm::vec3 v0(pose.v0_height);
        const auto local = [&](glm::vec3 v) {
            const glm::vec3 r = v - v0;
            return glm::vec3(glm::dot(r, d), glm::dot(r, up), glm::dot(r, w));
        };
        gpu::TileInstanceGpu g;
        g.place = glm::vec4(s.root_m.x, 0.f, s.root_m.z, s.directionAngle_rad);
        g.restV1_width = glm::vec4(local(glm::vec3(pose.v1_width)), pose.v1_width.w);
        g.restV2_height = glm::vec4(local(glm::vec3(pose.v2_stiffness)), pose.v0_height.w);
        g.look = glm::vec4(static_cast<float>(s.archetype), s.stiffness, thresholds.uniform(), 0.f);
        patch.push_back(g);
    }
    return patch;
}

float tallestBlade_m(const std::vector<gpu::TileInstanceGpu>& patch) {
    float tallest = 0.f;
    for (const gpu::TileInstanceGpu& g : patch) tallest = std::max(tallest, g.restV2_height.w);
    return tallest;
}

}  // namespace meadow::runtime
