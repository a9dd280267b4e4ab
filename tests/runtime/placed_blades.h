#pragma once
// Blades at known poses for the image tests of the blade surface: a scene around a tiny ground
// square, the caller's archetypes, and blades placed by hand (padded to whole patches with
// copies far below the ground, out of every view).
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "meadow/modeling/archetype.h"
#include "meadow/runtime/scene.h"
#include "patches.h"
#include "scene_gpu.h"
#include "seeding.h"
#include "support/scene_files.h"

namespace meadow::runtime::test {

struct PlacedBlade {
    glm::vec3 root_m{0.f};
    float directionAngle_rad = 0.f;  // 0: the width along world +X, the face toward +-Z
    std::uint32_t archetype = 0;
};

// A straight upright archetype of the given height and constant width, drawn with `shape`
// (two width samples: the analytic shape is used, not the profile).
inline modeling::Archetype uprightArchetype(float height_m, float width_m,
                                            modeling::AnalyticShape shape) {
    modeling::Archetype a;
    a.name = "upright";
    a.spine_m = {glm::vec3(0.f), glm::vec3(0.f, 0.5f * height_m, 0.f),
                 glm::vec3(0.f, height_m, 0.f)};
    a.width.width_m = {width_m, width_m};
    a.nearestShape = shape;
    return a;
}

// A scene seen from `camera_m` toward `target_m`: blue sky, a 1 cm ground square at the origin,
// no physics, no culling settings of note; `size_px` square images, `msaa` samples.
inline SceneDescription placedBladeScene(const std::string& name, glm::vec3 camera_m,
                                         glm::vec3 target_m, int size_px, int msaa,
                                         std::vector<modeling::Archetype> archetypes) {
    const auto dir = freshTestDirectory(name);
    writeQuad(dir / "ground.gltf", -0.005f, 0.005f, -0.005f, 0.005f);
    const nlohmann::json extra = {
        {"camera",
         {{"path",
           {{{"time_s", 0},
             {"position_m", {camera_m.x, camera_m.y, camera_m.z}},
             {"target_m", {target_m.x, target_m.y, target_m.z}}}}},
          {"vertical_fov_deg", 50},
          {"near_m", 0.05},
          {"far_m", 200}}},
        {"light", {{"sky_color", {0.1, 0.2, 0.9}}}},
        {"physics", {{"enabled", false}}},
        {"render", {{"size_px", {size_px, size_px}}, {"msaa_samples", msaa}, {"patch_size", 64}}}};
    SceneDescription scene =
        loadSceneDescription(writeScene(dir, minimalScene("ground.gltf", extra)));
    scene.archetypes = std::move(archetypes);
    scene.archetypeWeights.assign(scene.archetypes.size(), 1.f);
    return scene;
}

// The scene's meshes with `placed` as its blades instead of seeded ones.
inline SceneBlades placedBlades(const SceneDescription& scene,
                                const std::vector<PlacedBlade>& placed) {
    SceneBlades out;
    for (const SceneMesh& m : scene.grassMeshes)
        out.grassMeshes.push_back(loadGltfTriangles(m.gltf));
    out.patchSize = patchSizeOf(scene);
    std::vector<SeededBlade> seeds;
    for (const PlacedBlade& p : placed) {
        SeededBlade s;
        s.root_m = p.root_m;
        s.directionAngle_rad = p.directionAngle_rad;
        s.archetype = p.archetype;
        s.stiffness = 15.f;
        seeds.push_back(s);
    }
    while (seeds.size() % out.patchSize != 0) {
        SeededBlade hidden = seeds.front();
        hidden.root_m = glm::vec3(0.f, -1000.f, 0.f);
        seeds.push_back(hidden);
    }
    std::vector<glm::vec3> roots;
    std::vector<float> reach;
    for (const SeededBlade& s : seeds) {
        roots.push_back(s.root_m);
        reach.push_back(scene.archetypes[s.archetype].height_m());
    }
    const PatchLayout layout = buildPatches(roots, reach, out.patchSize);
    out.patches = layout.patches;
    for (std::uint32_t i : layout.order) {
        out.seeds.push_back(seeds[i]);
        out.blades.push_back(restPose(seeds[i], scene.archetypes[seeds[i].archetype]));
        out.rests.push_back(restState(seeds[i], out.blades.back()));
    }
    for (const modeling::Archetype& a : scene.archetypes)
        out.archetypes.push_back(archetypeForGpu(a, false));
    return out;
}

}  // namespace meadow::runtime::test
