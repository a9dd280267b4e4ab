// What seeding promises about where blades grow and what they are: the density map's grey levels
// become blades per area, tuft centres keep their Poisson-disk distance, archetype weights become
// frequencies.
#include <gtest/gtest.h>

#include <fstream>
#include <glm/geometric.hpp>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "meadow/runtime/error.h"
#include "meadow/runtime/scene.h"
#include "scene_gpu.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

// A 3 m x 1 m field under a map of three equal columns, black | mid grey (128) | white: blades
// per area in each column, away from the column borders. Tufts off, so every blade draws its own
// position and threshold.
TEST(SeedingDensityMap, GreyLevelsBecomeBladesPerAreaBlackGrowsNone) {
    const auto dir = test::freshTestDirectory("density_map");
    test::writeQuad(dir / "ground.gltf", 0.f, 3.f, 0.f, 1.f);
    cv::Mat map(1, 300, CV_8UC1);
    map.colRange(0, 100).setTo(0);
    map.colRange(100, 200).setTo(128);
    map.colRange(200, 300).setTo(255);
    ASSERT_TRUE(cv::imwrite((dir / "density.png").string(), map));
    constexpr float kDensity_per_m2 = 3000.f;
    const nlohmann::json extra = {
        {"blades",
         {{"density_per_m2", kDensity_per_m2},
          {"tuft_fraction", 0},
          {"seed", 8},
          {"density_map",
           {{"image", "density.png"}, {"min_xz_m", {0, 0}}, {"max_xz_m", {3, 1}}}}}}};
    const SceneBlades b = buildSceneBlades(
        loadSceneDescription(test::writeScene(dir, test::minimalScene("ground.gltf", extra))));

    // Columns [0, 1), [1, 2), [2, 3] m; 5 cm kept clear of each border (the nearest-texel
    // boundary lies within 0.5 texel = 5 mm of it).
    constexpr float kMargin_m = 0.05f;
    const double bandArea_m2 = (1.0 - 2.0 * kMargin_m) * 1.0;
    double count[3] = {0, 0, 0};
    for (const SeededBlade& s : b.seeds)
        for (int band = 0; band < 3; ++band)
            if (s.root_m.x > band + kMargin_m && s.root_m.x < band + 1 - kMargin_m) ++count[band];
    const double white_per_m2 = count[2] / bandArea_m2, grey_per_m2 = count[1] / bandArea_m2;
    std::cout << "blades per m^2 under map 0 / 128 / 255: " << count[0] / bandArea_m2 << " / "
              << grey_per_m2 << " / " << white_per_m2 << " (grey / white "
              << grey_per_m2 / white_per_m2 << ")\n";
    EXPECT_EQ(count[0], 0.0) << "map value 0 must grow nothing";
    EXPECT_NEAR(grey_per_m2 / white_per_m2, 128.0 / 255.0, 0.05);
    // The map thins the field, it does not move blades elsewhere: white keeps the scene density.
    EXPECT_NEAR(white_per_m2, kDensity_per_m2, 0.05 * kDensity_per_m2);
}

// A density map that is not an image fails when the scene loads (before any GL context), with
// the scene file, the field and the image in one line, as a bad archetype map does.
TEST(SeedingDensityMap, UnreadableMapFailsOnLoadNamingSceneFieldAndImage) {
    const auto dir = test::freshTestDirectory("density_map_unreadable");
    test::writeQuad(dir / "ground.gltf", 0.f, 1.f, 0.f, 1.f);
    std::ofstream(dir / "density.png") << "not an image";
    const nlohmann::json extra = {
        {"blades",
         {{"density_map",
           {{"image", "density.png"}, {"min_xz_m", {0, 0}}, {"max_xz_m", {1, 1}}}}}}};
    const auto scene = test::writeScene(dir, test::minimalScene("ground.gltf", extra));
    try {
        (void)loadSceneDescription(scene);
        FAIL() << "an unreadable density map was accepted";
    } catch (const RuntimeError& e) {
        const std::string message = e.what();
        for (const std::string& part :
             {scene.string(), std::string("blades.density_map.image"), std::string("density.png"),
              std::string("not a readable image")})
            EXPECT_NE(message.find(part), std::string::npos) << part << " missing in: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    }
}

TEST(SeedingTufts, TuftCentresAreAtLeastThePoissonDiskSpacingApart) {
    const auto dir = test::freshTestDirectory("poisson");
    test::writeQuad(dir / "ground.gltf", -2.f, 2.f, -2.f, 2.f);
    constexpr float kSpacing_m = 0.3f, kTuftRadius_m = 0.04f;
    const nlohmann::json extra = {{"blades",
                                   {{"density_per_m2", 600},
                                    {"tuft_fraction", 1},
                                    {"tuft_spacing_m", kSpacing_m},
                                    {"tuft_radius_m", kTuftRadius_m},
                                    {"seed", 9}}}};
    const SceneBlades b = buildSceneBlades(
        loadSceneDescription(test::writeScene(dir, test::minimalScene("ground.gltf", extra))));
    std::vector<glm::vec3> centres;
    for (const SeededBlade& s : b.seeds) {
        if (!s.inTuft) continue;
        EXPECT_LE(glm::distance(s.root_m, s.tuftCenter_m), kTuftRadius_m * 1.0001f);
        if (centres.empty() || centres.back() != s.tuftCenter_m) centres.push_back(s.tuftCenter_m);
    }
    std::sort(centres.begin(), centres.end(), [](glm::vec3 a, glm::vec3 c) {
        return std::tie(a.x, a.y, a.z) < std::tie(c.x, c.y, c.z);
    });
    centres.erase(std::unique(centres.begin(), centres.end()), centres.end());
    float nearest_m = 1e30f;
    for (std::size_t i = 0; i < centres.size(); ++i)
        for (std::size_t j = i + 1; j < centres.size(); ++j)
            nearest_m = std::min(nearest_m, glm::distance(centres[i], centres[j]));
    std::cout << centres.size() << " tufts, nearest centres " << nearest_m << " m apart (spacing "
              << kSpacing_m << " m)\n";
    // 16 m^2 at 0.3 m: random dart throwing saturates near 0.55 of hexagonal packing
    // (~205 disks), so well over 100 tufts must have been placed for the test to mean anything.
    EXPECT_GT(centres.size(), 100u);
    EXPECT_GE(nearest_m, kSpacing_m * (1.f - 1e-4f));
}

TEST(SeedingArchetypes, WeightsThreeToOneGiveThreeQuartersOfTheBlades) {
    const auto dir = test::freshTestDirectory("weights");
    test::writeQuad(dir / "ground.gltf", -1.f, 1.f, -1.f, 1.f);
    const nlohmann::json extra = {{"archetypes",
                                   {{"library", "default"},
                                    {"weights",
                                     {{"default-upright", 3},
                                      {"default-arched", 1},
                                      {"default-short", 0},
                                      {"default-broad", 0}}}}},
                                  {"blades", {{"density_per_m2", 1000}, {"seed", 10}}}};
    const SceneDescription scene =
        loadSceneDescription(test::writeScene(dir, test::minimalScene("ground.gltf", extra)));
    const SceneBlades b = buildSceneBlades(scene);
    ASSERT_EQ(scene.archetypes[0].name, "default-upright");
    ASSERT_EQ(scene.archetypes[1].name, "default-arched");
    std::size_t perArchetype[4] = {0, 0, 0, 0};
    for (const SeededBlade& s : b.seeds) ++perArchetype[s.archetype];
    const double upright = static_cast<double>(perArchetype[0]) / b.seeds.size();
    std::cout << b.seeds.size() << " blades, fraction default-upright " << upright << '\n';
    EXPECT_GT(b.seeds.size(), 3000u);
    EXPECT_NEAR(upright, 0.75, 0.05);
    EXPECT_EQ(perArchetype[0] + perArchetype[1], b.seeds.size()) << "weight 0 grew blades";
}

}  // namespace
}  // namespace meadow::runtime
