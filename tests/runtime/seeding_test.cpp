// Blade seeding on triangle meshes: area-weighted, deterministic, rest poses on the surface.
#include "../../runtime/src/seeding.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <map>

#include "../../runtime/src/scene_gpu.h"
#include "meadow/runtime/error.h"
#include "meadow/runtime/scene.h"
#include "scene_test_helpers.h"

namespace meadow::runtime {
namespace {

TEST(Seeding, SampleMeadowBladesHaveArchetypeSizedPoses) {
    const SceneDescription scene =
        loadSceneDescription(MEADOW_SOURCE_DIR "/samples/scenes/meadow.json");
    const SceneBlades b = buildSceneBlades(scene);
    ASSERT_EQ(b.blades.size() % b.patchSize, 0u);
    for (std::size_t i = 0; i < b.blades.size(); ++i) {
        const gpu::BladeGpu& g = b.blades[i];
        const float h = g.v0_height.w;
        const float reach = glm::length(glm::vec3(g.v2_stiffness) - glm::vec3(g.v0_height));
        ASSERT_GT(h, 0.05f) << i;
        ASSERT_LT(h, 0.7f) << i;
        ASSERT_LE(reach, h * 1.001f) << "tip farther than the blade is long, blade " << i;
        ASSERT_GT(g.v1_width.w, 0.002f) << i;
        ASSERT_LT(g.v1_width.w, 0.02f) << i;
        ASSERT_NEAR(glm::length(glm::vec3(g.up_direction)), 1.f, 1e-4f) << i;
    }
}

}  // namespace
}  // namespace meadow::runtime
