#pragma once
// Small scenes for the runtime tests: glTF files written on the fly, scene JSON around them.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/test_util.h"

namespace meadow::runtime::test {

// Private to this process: ctest runs each test in its own process, several at once, and a
// folder shared by name could be removed under a test still reading it.
inline std::filesystem::path freshTestDirectory(const std::string& name) {
    return meadow::test::freshTempDir("runtime_test_" + name);
}

// A .gltf with its buffer in "<name>.bin" next to it: positions (m) and triangles.
inline void writeGltf(const std::filesystem::path& gltf, const std::vector<glm::vec3>& positions,
                      const std::vector<std::uint32_t>& indices) {
    const std::filesystem::path bin = std::filesystem::path(gltf).replace_extension(".bin");
    std::ofstream b(bin, std::ios::binary);
    b.write(reinterpret_cast<const char*>(positions.data()),
            static_cast<std::streamsize>(positions.size() * 12));
    b.write(reinterpret_cast<const char*>(indices.data()),
            static_cast<std::streamsize>(indices.size() * 4));
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : positions)
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    const nlohmann::json j = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes",
         {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"mode", 4}}}}}}},
        {"buffers",
         {{{"uri", bin.filename().string()},
           {"byteLength", positions.size() * 12 + indices.size() * 4}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", positions.size() * 12}},
          {{"buffer", 0},
           {"byteOffset", positions.size() * 12},
           {"byteLength", indices.size() * 4}}}},
        {"accessors",
         {{{"bufferView", 0},
           {"componentType", 5126},
           {"count", positions.size()},
           {"type", "VEC3"},
           {"min", {lo.x, lo.y, lo.z}},
           {"max", {hi.x, hi.y, hi.z}}},
          {{"bufferView", 1},
           {"componentType", 5125},
           {"count", indices.size()},
           {"type", "SCALAR"}}}}};
    std::ofstream(gltf) << j.dump(1);
}

// A flat square [x0, x1] x [z0, z1] at height y, two triangles facing +Y.
inline void writeQuad(const std::filesystem::path& gltf, float x0, float x1, float z0, float z1,
                      float y = 0.f) {
    writeGltf(gltf, {{x0, y, z0}, {x1, y, z0}, {x0, y, z1}, {x1, y, z1}}, {0, 2, 1, 1, 2, 3});
}

// A minimal valid scene around one grass mesh; `extra` fields are merged over it.
inline nlohmann::json minimalScene(const std::string& gltf,
                                   const nlohmann::json& extra = nlohmann::json::object()) {
    nlohmann::json j = {
        {"format", "meadow.scene"},
        {"version", 1},
        {"grass", {{{"gltf", gltf}}}},
        {"blades", {{"density_per_m2", 200}, {"seed", 3}}},
        {"render", {{"size_px", {96, 64}}, {"msaa_samples", 2}, {"patch_size", 64}}}};
    j.merge_patch(extra);
    return j;
}

inline std::filesystem::path writeScene(const std::filesystem::path& dir,
                                        const nlohmann::json& scene,
                                        const std::string& name = "scene.json") {
    std::ofstream(dir / name) << scene.dump(1);
    return dir / name;
}

// Grass on a 1 m square (written to dir/ground.gltf) seen from the side and above: the lower
// half of a 96 x 64 image is the meadow, the top rows are sky. `extra` is merged over it.
inline std::filesystem::path writeSmallMeadow(
    const std::filesystem::path& dir, const nlohmann::json& extra = nlohmann::json::object()) {
    writeQuad(dir / "ground.gltf", -0.5f, 0.5f, -0.5f, 0.5f);
    nlohmann::json settings = {
        {"blades", {{"density_per_m2", 400}, {"tuft_fraction", 0.5}, {"seed", 2}}},
        {"camera",
         {{"position_m", {0, 0.45, 0.9}}, {"target_m", {0, 0.05, 0}}, {"vertical_fov_deg", 50}}},
        {"light", {{"sky_color", {0.6, 0.75, 0.9}}}},
        {"render", {{"size_px", {96, 64}}, {"msaa_samples", 2}, {"patch_size", 64}}}};
    settings.merge_patch(extra);
    return writeScene(dir, minimalScene("ground.gltf", settings));
}

// Grass green in an 8-bit BGR image: green clearly above red and blue.
inline bool isGreen(std::uint8_t b, std::uint8_t g, std::uint8_t r) {
    return g > r + 10 && g > b + 10;
}

}  // namespace meadow::runtime::test
