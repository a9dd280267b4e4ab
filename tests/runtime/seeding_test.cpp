// Blade seeding on triangle meshes: area-weighted, deterministic, rest poses on the surface.
#include "seeding.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <map>

#include "meadow/runtime/error.h"
#include "meadow/runtime/scene.h"
#include "scene_gpu.h"
#include "support/scene_files.h"

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

namespace meadow::runtime {
namespace {

// Four triangles of areas 0.5, 1.5, 3 and 5 m^2 side by side in the y = 0 plane.
std::vector<glm::vec3> unequalTrianglePositions() {
    return {{0, 0, 0},  {0, 0, 1},  {1, 0, 0},    // 0.5
            {2, 0, 0},  {2, 0, 1},  {5, 0, 0},    // 1.5
            {6, 0, 0},  {6, 0, 2},  {9, 0, 0},    // 3
            {10, 0, 0}, {10, 0, 2}, {15, 0, 0}};  // 5
}

SceneDescription unequalScene(const std::string& name, float tuftFraction) {
    const auto dir = test::freshTestDirectory(name);
    test::writeGltf(dir / "tris.gltf", unequalTrianglePositions(),
                    {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11});
    nlohmann::json extra = {
        {"blades", {{"density_per_m2", 400}, {"tuft_fraction", tuftFraction}, {"seed", 11}}}};
    return loadSceneDescription(test::writeScene(dir, test::minimalScene("tris.gltf", extra)));
}

TEST(Seeding, SingleBladesAreAreaWeightedChiSquare) {
    const SceneBlades b = buildSceneBlades(unequalScene("area", 0.f));
    const double areas[] = {0.5, 1.5, 3.0, 5.0};
    std::map<std::uint32_t, double> counts;
    for (const SeededBlade& s : b.seeds) counts[s.triangle] += 1;
    const double n = static_cast<double>(b.seeds.size());
    double chi2 = 0.0;
    for (std::uint32_t t = 0; t < 4; ++t) {
        const double expected = n * areas[t] / 10.0;
        chi2 += (counts[t] - expected) * (counts[t] - expected) / expected;
    }
    // 3 degrees of freedom: P(chi2 > 16.27) = 0.001 for a truly area-weighted sampler.
    EXPECT_LT(chi2, 16.27) << "counts " << counts[0] << " " << counts[1] << " " << counts[2] << " "
                           << counts[3] << " of " << n;
    EXPECT_NEAR(n, 400.0 * 10.0, 64.0) << "density x area, topped up to whole patches";
}

TEST(Seeding, SameSceneSameBlades) {
    const SceneBlades a = buildSceneBlades(unequalScene("det_a", 0.5f));
    const SceneBlades b = buildSceneBlades(unequalScene("det_b", 0.5f));
    ASSERT_EQ(a.blades.size(), b.blades.size());
    for (std::size_t i = 0; i < a.blades.size(); ++i) {
        ASSERT_EQ(a.blades[i].v0_height, b.blades[i].v0_height) << i;
        ASSERT_EQ(a.blades[i].v2_stiffness, b.blades[i].v2_stiffness) << i;
        ASSERT_EQ(a.rests[i].restV1_archetype, b.rests[i].restV1_archetype) << i;
    }
}

TEST(Seeding, RootsLieOnTheSurfaceAndGrowAlongItsNormal) {
    const SceneBlades b = buildSceneBlades(unequalScene("surface", 0.f));
    for (const gpu::BladeGpu& g : b.blades) {
        ASSERT_NEAR(g.v0_height.y, 0.f, 1e-5f);
        ASSERT_NEAR(g.up_direction.y, 1.f, 1e-5f);
        ASSERT_GT(g.v2_stiffness.y, 0.f) << "the tip is above the ground";
    }
}

TEST(Seeding, TuftsAreSeededAndMeshWithoutAreaIsAnError) {
    const SceneBlades b = buildSceneBlades(unequalScene("tufts", 1.f));
    std::size_t inTufts = 0;
    for (const SeededBlade& s : b.seeds) inTufts += s.inTuft;
    EXPECT_GT(inTufts, b.seeds.size() / 2);

    const auto dir = test::freshTestDirectory("no_area");
    test::writeGltf(dir / "flat.gltf", {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {0, 1, 2});  // collinear
    const SceneDescription scene =
        loadSceneDescription(test::writeScene(dir, test::minimalScene("flat.gltf")));
    try {
        buildSceneBlades(scene);
        FAIL() << "a mesh without area grew grass";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("no surface area"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("flat.gltf"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace meadow::runtime
