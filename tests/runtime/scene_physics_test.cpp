// The scene file reaches every physics term PhysicsSettings has: the wind wave and point source,
// the gravity direction, centre and mix. Out-of-range values and the old misnamed wind field are
// one clear line.
#include <gtest/gtest.h>

#include "meadow/runtime/error.h"
#include "meadow/runtime/scene.h"
#include "physics_scene_pass.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

nlohmann::json windAndGravity() {
    return {{"wind",
             {{"direction", {0, 0, 2}},
              {"wave_amplitude_m_s", 3.5},
              {"wavelength_m", 7},
              {"frequency_hz", 0.25},
              {"source_m", {1, 2, 3}},
              {"source_amplitude_m_s", 6},
              {"source_radius_m", 9}}},
            {"physics",
             {{"gravity_direction", {0, -2, 0}},
              {"gravity_m_s2", 3.7},
              {"gravity_center_m", {0, -100, 5}},
              {"gravity_center_m_s2", 1.6},
              {"gravity_center_mix", 0.4},
              {"collision_decay_per_s", 2}}}};
}

// The wind direction and amplitude travel through the frame uniforms, as the renderer fills them.
gpu::FrameGpu frameOf(const SceneDescription& scene) {
    gpu::FrameGpu frame{};
    frame.wind = glm::vec4(scene.wind.direction, scene.wind.waveAmplitude_m_s);
    return frame;
}

TEST(ScenePhysics, WindAndGravityFieldsParseIntoThePhysicsSettings) {
    const auto dir = test::freshTestDirectory("scene_physics");
    test::writeQuad(dir / "ground.gltf", 0, 1, 0, 1);
    const SceneDescription scene = loadSceneDescription(
        test::writeScene(dir, test::minimalScene("ground.gltf", windAndGravity())));
    const PhysicsSettings s = physicsSettingsOf(scene, frameOf(scene));
    EXPECT_EQ(s.windDirection, glm::vec3(0, 0, 1));
    EXPECT_FLOAT_EQ(s.windWave_mps, 3.5f);
    EXPECT_FLOAT_EQ(s.windWavelength_m, 7.f);
    EXPECT_FLOAT_EQ(s.windFrequency_hz, 0.25f);
    EXPECT_EQ(s.windSource_m, glm::vec3(1, 2, 3));
    EXPECT_FLOAT_EQ(s.windSource_mps, 6.f);
    EXPECT_FLOAT_EQ(s.windSourceRadius_m, 9.f);
    EXPECT_EQ(s.gravityDirection, glm::vec3(0, -1, 0));
    EXPECT_FLOAT_EQ(s.gravity_mps2, 3.7f);
    EXPECT_EQ(s.gravityCenter_m, glm::vec3(0, -100, 5));
    EXPECT_FLOAT_EQ(s.gravityCenter_mps2, 1.6f);
    EXPECT_FLOAT_EQ(s.gravityCenterMix, 0.4f);
    EXPECT_FLOAT_EQ(s.etaDecay_per_s, 2.f);
}

TEST(ScenePhysics, WithoutTheFieldsTheSettingsAreThePhysicsDefaults) {
    const auto dir = test::freshTestDirectory("scene_physics_defaults");
    test::writeQuad(dir / "ground.gltf", 0, 1, 0, 1);
    const SceneDescription scene =
        loadSceneDescription(test::writeScene(dir, test::minimalScene("ground.gltf")));
    const PhysicsSettings s = physicsSettingsOf(scene, frameOf(scene));
    const PhysicsSettings d;
    EXPECT_EQ(s.gravityCenter_m, d.gravityCenter_m);
    EXPECT_EQ(s.gravityCenterMix, 0.f);
    EXPECT_EQ(s.windSource_mps, 0.f) << "no point source unless the scene asks for one";
    EXPECT_EQ(s.windWavelength_m, d.windWavelength_m);
    EXPECT_EQ(s.windWave_mps, 2.f) << "the scene's default wave amplitude";
}

TEST(ScenePhysics, OutOfRangeAndRenamedFieldsAreOneClearLine) {
    const auto dir = test::freshTestDirectory("scene_physics_errors");
    test::writeQuad(dir / "ground.gltf", 0, 1, 0, 1);
    struct Case {
        const char* block;
        const char* field;
        nlohmann::json value;
        std::string expected;
    };
    for (const Case& c :
         {Case{"physics", "gravity_center_mix", 1.5,
               "physics.gravity_center_mix: must lie in [0, 1], got 1.5"},
          Case{"physics", "gravity_center_m_s2", -1, "physics.gravity_center_m_s2"},
          Case{"physics",
               "gravity_center_m",
               {0, 1},
               "physics.gravity_center_m: must be an array of 3 numbers"},
          Case{"physics", "gravity_direction", {0, 0, 0}, "must not be zero"},
          Case{"wind", "source_radius_m", 0, "wind.source_radius_m"},
          Case{"wind", "wavelength_m", -2, "wind.wavelength_m"},
          Case{"wind", "wave_amplitude_m_s", -1, "wind.wave_amplitude_m_s"},
          Case{"wind", "strength_m_s2", 2, "renamed to wave_amplitude_m_s"},
          Case{"wind", "source_amplitude", 2, "wind.source_amplitude: unknown field"}}) {
        nlohmann::json scene = test::minimalScene("ground.gltf", windAndGravity());
        scene[c.block][c.field] = c.value;
        std::string message;
        try {
            loadSceneDescription(test::writeScene(dir, scene));
        } catch (const RuntimeError& e) {
            message = e.what();
        }
        EXPECT_NE(message.find(c.expected), std::string::npos) << c.field << " got: " << message;
        EXPECT_NE(message.find("scene.json"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace meadow::runtime
