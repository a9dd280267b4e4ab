// archetypes.map: an 8-bit grey image over world XZ whose value k plants archetype k (255: by
// weight). It decides which archetype grows where and nothing else; a bad map fails on load
// with one line naming the scene, the field and the image.
#include <gtest/gtest.h>

#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "meadow/runtime/error.h"
#include "meadow/runtime/scene.h"
#include "scene_gpu.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

// A 2 m x 2 m field (x, z in [-1, 1]) and a map over exactly that square.
struct MapScene {
    std::filesystem::path dir;
    nlohmann::json scene;
};

MapScene fieldWithMap(const std::string& name, const cv::Mat& map) {
    MapScene m{test::freshTestDirectory(name), {}};
    test::writeQuad(m.dir / "ground.gltf", -1.f, 1.f, -1.f, 1.f);
    if (!map.empty()) cv::imwrite((m.dir / "archetypes.png").string(), map);
    nlohmann::json extra = {{"blades", {{"density_per_m2", 1000}, {"seed", 12}}}};
    if (!map.empty())
        extra["archetypes"] = {
            {"library", "default"},
            {"map", {{"image", "archetypes.png"}, {"min_xz_m", {-1, -1}}, {"max_xz_m", {1, 1}}}}};
    m.scene = test::minimalScene("ground.gltf", extra);
    return m;
}

SceneBlades seed(const MapScene& m) {
    return buildSceneBlades(loadSceneDescription(test::writeScene(m.dir, m.scene)));
}

// Left half (x < 0) value 0, right half value 1.
cv::Mat twoHalves() {
    cv::Mat map(64, 64, CV_8UC1, cv::Scalar(0));
    map.colRange(32, 64).setTo(1);
    return map;
}

TEST(ArchetypeMap, TwoHalvesPlantArchetypeZeroLeftAndOneRight) {
    const SceneBlades b = seed(fieldWithMap("archetype_map_halves", twoHalves()));
    // The nearest-texel border of the 64-texel map lies at x = 0 exactly; 2 cm kept clear.
    double left = 0, leftZero = 0, right = 0, rightOne = 0;
    for (const SeededBlade& s : b.seeds) {
        if (s.root_m.x < -0.02f) ++left, leftZero += s.archetype == 0;
        if (s.root_m.x > 0.02f) ++right, rightOne += s.archetype == 1;
    }
    std::cout << "archetype 0 on the left: " << leftZero << " / " << left
              << ", archetype 1 on the right: " << rightOne << " / " << right << '\n';
    ASSERT_GT(left, 1000);
    ASSERT_GT(right, 1000);
    EXPECT_GE(leftZero / left, 0.99);
    EXPECT_GE(rightOne / right, 0.99);
}

TEST(ArchetypeMap, MapChangesArchetypesOnlyAndValue255FallsBackToWeights) {
    const SceneBlades none = seed(fieldWithMap("archetype_map_none", {}));
    const SceneBlades halves = seed(fieldWithMap("archetype_map_same_seed", twoHalves()));
    const SceneBlades byWeights =
        seed(fieldWithMap("archetype_map_255", cv::Mat(8, 8, CV_8UC1, cv::Scalar(255))));
    ASSERT_EQ(none.seeds.size(), halves.seeds.size());
    ASSERT_EQ(none.seeds.size(), byWeights.seeds.size());
    std::size_t changed = 0;
    for (std::size_t i = 0; i < none.seeds.size(); ++i) {
        ASSERT_EQ(none.seeds[i].root_m, halves.seeds[i].root_m) << i;
        ASSERT_EQ(none.seeds[i].heightScale, halves.seeds[i].heightScale) << i;
        ASSERT_EQ(none.seeds[i].directionAngle_rad, halves.seeds[i].directionAngle_rad) << i;
        ASSERT_EQ(none.seeds[i].archetype, byWeights.seeds[i].archetype) << i;
        changed += none.seeds[i].archetype != halves.seeds[i].archetype;
    }
    EXPECT_GT(changed, none.seeds.size() / 2) << "the map changed almost nothing";
}

TEST(ArchetypeMap, BadMapsGiveOneClearLineNamingSceneFieldAndImage) {
    MapScene m = fieldWithMap("archetype_map_errors", twoHalves());
    cv::imwrite((m.dir / "deep.png").string(), cv::Mat(4, 4, CV_16UC1, cv::Scalar(1)));
    cv::imwrite((m.dir / "colour.png").string(), cv::Mat(4, 4, CV_8UC3, cv::Scalar(1, 1, 1)));
    cv::Mat outOfRange(4, 4, CV_8UC1, cv::Scalar(0));
    outOfRange.at<std::uint8_t>(2, 3) = 4;  // the default set has archetypes 0..3
    cv::imwrite((m.dir / "range.png").string(), outOfRange);
    std::ofstream(m.dir / "text.png") << "not an image";

    struct Case {
        std::string image, expected;
    };
    for (const Case& c :
         {Case{"absent.png", "does not exist"}, Case{"deep.png", "16-bit"},
          Case{"colour.png", "3 channel"}, Case{"range.png", "value 4 at column 3, row 2"},
          Case{"text.png", "not a readable image"}}) {
        nlohmann::json scene = m.scene;
        scene["archetypes"]["map"]["image"] = c.image;
        std::string message;
        try {
            loadSceneDescription(test::writeScene(m.dir, scene));
        } catch (const RuntimeError& e) {
            message = e.what();
        }
        SCOPED_TRACE(c.image);
        EXPECT_NE(message.find(c.expected), std::string::npos) << "got: " << message;
        EXPECT_NE(message.find("scene.json"), std::string::npos) << message;
        EXPECT_NE(message.find("archetypes.map.image"), std::string::npos) << message;
        EXPECT_NE(message.find(c.image), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    nlohmann::json typo = m.scene;
    typo["archetypes"]["map"]["max_xz"] = {1, 1};
    EXPECT_THROW(loadSceneDescription(test::writeScene(m.dir, typo)), RuntimeError);
}

}  // namespace
}  // namespace meadow::runtime
