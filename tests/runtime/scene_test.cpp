// Scene files: what is read, and the clear errors for what is wrong.
#include "meadow/runtime/scene.h"

#include <gtest/gtest.h>

#include "meadow/runtime/error.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

std::string errorOf(const std::filesystem::path& dir, const nlohmann::json& scene) {
    try {
        loadSceneDescription(test::writeScene(dir, scene));
    } catch (const RuntimeError& e) {
        return e.what();
    }
    return "";
}

TEST(SceneFile, SampleSceneLoadsWithItsSettings) {
    const SceneDescription s =
        loadSceneDescription(MEADOW_SOURCE_DIR "/samples/scenes/meadow.json");
    EXPECT_EQ(s.grassMeshes.size(), 1u);
    EXPECT_EQ(s.archetypes.size(), s.archetypeWeights.size());
    EXPECT_EQ(s.camera.path.size(), 2u);
    EXPECT_EQ(s.render.width_px, 640);
    EXPECT_EQ(s.render.height_px, 360);
    EXPECT_EQ(s.colliders.size(), 1u);
    EXPECT_FLOAT_EQ(s.blades.density_per_m2, 150.f);
}

TEST(SceneFile, BadFilesGiveOneClearLineNamingFileAndField) {
    const auto dir = test::freshTestDirectory("scene_errors");
    test::writeQuad(dir / "ground.gltf", 0, 1, 0, 1);
    const nlohmann::json good = test::minimalScene("ground.gltf");
    EXPECT_EQ(errorOf(dir, good), "");

    struct Case {
        nlohmann::json scene;
        std::string expected;
    };
    nlohmann::json wrongFormat = good, newVersion = good, typo = good, missingMesh = good,
                   missingLibrary = good, badRange = good, outOfRange = good;
    wrongFormat["format"] = "meadow.archetype-library";
    newVersion["version"] = 2;
    typo["blades"]["densty_per_m2"] = 5;
    missingMesh["grass"][0]["gltf"] = "nowhere.glb";
    missingLibrary["archetypes"] = {{"library", "no_library.json"}};
    badRange["blades"]["height_scale"] = {2.0, 1.0};
    outOfRange["blades"]["density_per_m2"] = -5;
    for (const Case& c :
         {Case{wrongFormat, "format"}, Case{newVersion, "version 2 is not supported"},
          Case{typo, "blades.densty_per_m2: unknown field"}, Case{missingMesh, "nowhere.glb"},
          Case{missingLibrary, "no_library.json"}, Case{badRange, "blades.height_scale"},
          Case{outOfRange, "blades.density_per_m2: must lie in [0, 100000], got -5"}}) {
        const std::string message = errorOf(dir, c.scene);
        EXPECT_NE(message.find(c.expected), std::string::npos) << "got: " << message;
        EXPECT_NE(message.find("scene.json"), std::string::npos) << "names the file: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        // Written for the person who made the file, not the programmer: no C++ names.
        EXPECT_EQ(message.find("meadow::"), std::string::npos) << "got: " << message;
    }
    std::ofstream(dir / "broken.json") << "{ not json";
    EXPECT_THROW(loadSceneDescription(dir / "broken.json"), RuntimeError);
    EXPECT_THROW(loadSceneDescription(dir / "absent.json"), RuntimeError);
}

}  // namespace
}  // namespace meadow::runtime
