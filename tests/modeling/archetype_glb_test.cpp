#include "meadow/modeling/archetype_glb.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "meadow/modeling/error.h"
#include "support/test_util.h"

namespace fs = std::filesystem;
using namespace meadow::modeling;

namespace {

ArchetypeLibrary twoBladeLibrary() {
    ArchetypeLibrary lib;
    Archetype leaf;
    leaf.name = "leaf";
    leaf.spine_m = {{0, 0, 0}, {0.01f, 0.10f, 0}, {0.06f, 0.18f, 0.002f}};
    leaf.width.width_m = {0.012f, 0.018f, 0.016f, 0.009f, 0.0f};
    Archetype grass;
    grass.name = "grass";
    grass.spine_m = {{0, 0, 0}, {0, 0.15f, 0}, {0.03f, 0.28f, 0}};
    grass.width.width_m = {0.004f, 0.0035f, 0.001f};
    grass.nearestShape = AnalyticShape::Triangle;
    lib.archetypes = {leaf, grass};
    return lib;
}

}  // namespace

TEST(ArchetypeGlb, LoadsBackWithOneMeshPerArchetypeAndItsFitDataInExtras) {
    const std::string bytes = archetypeGlbBytes(twoBladeLibrary());
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromMemory(&model, &err, &warn,
                                            reinterpret_cast<const unsigned char*>(bytes.data()),
                                            static_cast<unsigned>(bytes.size())))
        << err;
    ASSERT_EQ(model.meshes.size(), 2u);
    EXPECT_EQ(model.meshes[0].name, "leaf");
    EXPECT_EQ(model.nodes[1].extras.Get("name").Get<std::string>(), "grass");
    EXPECT_EQ(model.nodes[1].extras.Get("nearest_shape").Get<std::string>(), "triangle");
    // The leaf's mesh spans its spine: from the root (y = 0) up to the tip (y = 0.18 m).
    const tinygltf::Accessor& pos =
        model.accessors[model.meshes[0].primitives[0].attributes.at("POSITION")];
    // The base ring is perpendicular to the tilted base tangent (0.01, 0.10), so it dips below
    // y = 0 by half the base width times that tilt: 0.006 m * 0.0995 = 0.6 mm.
    EXPECT_NEAR(pos.minValues[1], -0.0006, 0.0001);
    EXPECT_NEAR(pos.maxValues[1], 0.18, 0.01);
}

TEST(ArchetypeGlb, KhronosValidatorReportsNoErrors) {
    const fs::path validator = fs::path(MEADOW_SOURCE_DIR) / "tools" / "validate_gltf.mjs";
    const fs::path module =
        fs::path(MEADOW_SOURCE_DIR) / "tools" / "node_modules" / "gltf-validator";
    ASSERT_TRUE(fs::exists(module))
        << "the Khronos glTF validator is not installed: run ./meadow.sh test "
           "(or `npm install` in tools/)";
    const fs::path dir = meadow::test::freshTempDir("glb_test");
    const fs::path glb = dir / "library.glb";
    exportArchetypeGlb(twoBladeLibrary(), glb);
    const meadow::test::CommandResult r =
        meadow::test::runCommand("node " + validator.string() + " " + glb.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const auto report = nlohmann::json::parse(r.output);
    EXPECT_EQ(report["errors"], 0) << r.output;
    EXPECT_EQ(report["warnings"], 0) << r.output;
}

TEST(ArchetypeGlb, EmptyLibraryIsRefused) {
    EXPECT_THROW(archetypeGlbBytes(ArchetypeLibrary{}), ModelingError);
}
