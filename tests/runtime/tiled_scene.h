#pragma once
// A small tiled scene for the tile-instancing tests: a terrain 60 m square, tiles of 2 m, the
// default archetypes; `extra` is merged over it.
#include <nlohmann/json.hpp>

#include "meadow/runtime/scene.h"
#include "support/scene_files.h"

namespace meadow::runtime::test {

inline nlohmann::json tiledSceneJson(const nlohmann::json& extra = nlohmann::json::object()) {
    nlohmann::json j = {
        {"format", "meadow.scene"},
        {"version", 1},
        {"terrain",
         {{"min_xz_m", {-30, -30}},
          {"max_xz_m", {30, 30}},
          {"samples", 61},
          {"relief_m", 0.5},
          {"feature_size_m", 20},
          {"seed", 2}}},
        {"tiling",
         {{"tile_size_m", 2},
          {"near_distance_m", 12},
          {"transition_m", 3},
          {"full_density_distance_m", 4},
          {"active_distance_m", 2},
          {"pool_tiles", 16},
          {"max_drawn_blades", 65536}}},
        {"blades", {{"density_per_m2", 150}, {"seed", 3}}},
        {"camera", {{"position_m", {0, 1.5, 6}}, {"target_m", {0, 0, 0}}, {"far_m", 200}}},
        {"physics", {{"enabled", false}}},
        {"culling", {{"occlusion", false}}},
        {"render", {{"size_px", {160, 96}}, {"msaa_samples", 2}}}};
    j.merge_patch(extra);
    return j;
}

inline SceneDescription tiledScene(const std::string& name,
                                   const nlohmann::json& extra = nlohmann::json::object()) {
    return loadSceneDescription(writeScene(freshTestDirectory(name), tiledSceneJson(extra)));
}

}  // namespace meadow::runtime::test
