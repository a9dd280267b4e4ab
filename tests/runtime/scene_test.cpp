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

namespace meadow::runtime {
namespace {

TEST(SceneFile, MeshCollidersFollowTheirPathAndSpheresTheirVelocity) {
    const auto dir = test::freshTestDirectory("scene_colliders");
    test::writeQuad(dir / "ground.gltf", 0, 1, 0, 1);
    const nlohmann::json scene = test::minimalScene(
        "ground.gltf",
        {{"colliders",
          {{{"gltf", "ground.gltf"},
            {"spheres", 8},
            {"visible", false},
            {"path",
             {{{"time_s", 1}, {"position_m", {0, 0, 0}}},
              {{"time_s", 3}, {"position_m", {2, 0, 4}}}}}},
           {{"center_m", {1, 0.3, 0}}, {"radius_m", 0.3}, {"velocity_m_s", {0.5, 0, 0}}}}}});
    const SceneDescription s = loadSceneDescription(test::writeScene(dir, scene));
    ASSERT_EQ(s.colliders.size(), 2u);
    const ColliderDescription& mesh = s.colliders[0];
    ASSERT_TRUE(mesh.gltf.has_value());
    EXPECT_EQ(mesh.gltf->filename(), "ground.gltf");
    EXPECT_TRUE(mesh.gltf->is_absolute() || mesh.gltf->parent_path() == dir);
    EXPECT_EQ(mesh.maxSpheres, 8);
    EXPECT_FALSE(mesh.visible);
    EXPECT_EQ(mesh.positionAt(0.f), glm::vec3(0, 0, 0));  // held before the first key
    EXPECT_EQ(mesh.positionAt(2.f), glm::vec3(1, 0, 2));
    EXPECT_EQ(mesh.positionAt(9.f), glm::vec3(2, 0, 4));  // and after the last
    const ColliderDescription& sphere = s.colliders[1];
    EXPECT_FALSE(sphere.gltf.has_value());
    EXPECT_TRUE(sphere.visible);
    EXPECT_EQ(sphere.positionAt(2.f), glm::vec3(2, 0.3f, 0));
}

TEST(SceneFile, CollidersThatMixSphereMeshAndMotionFieldsAreRefused) {
    const auto dir = test::freshTestDirectory("scene_collider_errors");
    test::writeQuad(dir / "ground.gltf", 0, 1, 0, 1);
    const nlohmann::json key = {{"time_s", 0}, {"position_m", {0, 0, 0}}};
    const nlohmann::json later = {{"time_s", 0}, {"position_m", {1, 0, 0}}};
    struct Case {
        nlohmann::json collider;
        std::string expected;
    };
    for (const Case& c : {
             Case{{{"gltf", "ground.gltf"}, {"radius_m", 0.2}}, "colliders[0].radius_m"},
             Case{{{"radius_m", 0.2}, {"spheres", 4}}, "colliders[0].spheres"},
             Case{{{"velocity_m_s", {1, 0, 0}}, {"path", {key}}}, "not both"},
             Case{{{"path", {key, later}}}, "increasing time"},
             Case{{{"gltf", "ground.gltf"}, {"spheres", 1000}}, "colliders[0].spheres"},
         }) {
        const std::string message =
            errorOf(dir, test::minimalScene("ground.gltf", {{"colliders", {c.collider}}}));
        EXPECT_NE(message.find(c.expected), std::string::npos)
            << c.collider.dump() << " gave: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace meadow::runtime
