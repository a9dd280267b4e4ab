// Reading a scanned plant (scanned_plant.h): on a made plant of known organs, the stem is found
// from the geometry, up turns along it, and each leaf's length and width come out as made; bad
// files are one clear error. On the shared Label3DMaize and Pheno4D scans (skipped when absent):
// the stem is the organ the authors labelled first (Label3DMaize) or organ 0 of the skeleton, and
// every leaf's centre line runs along its own points.
#include "meadow/synth/scanned_plant.h"

#include <gtest/gtest.h>

#include <fstream>
#include <glm/geometric.hpp>

#include "meadow/synth/error.h"
#include "support/made_plant.h"
#include "support/shared_data.h"
#include "support/test_util.h"

namespace meadow::synth {
namespace {

// Lengths along the centre line: the last bin's centroid falls short of the tip by half a bin.
constexpr float kLengthTolerance = 0.03f;
constexpr float kWidthTolerance = 0.12f;

TEST(ScannedPlant, AMadePlantsStemUpAndLeavesComeOutAsMade) {
    const auto dir = test::freshTempDir("scanned_plant");
    const ScannedPlant plant = loadScannedPlant(test::writeMadePlant(dir / "made.txt"));
    EXPECT_EQ(plant.stemLabel, 1) << plant.stemFoundBy;
    ASSERT_EQ(plant.organs.size(), 3u);
    // Up is along the stem, the foot at the origin: the stem's points span y = 0 to its height.
    float lowest = 1e9f, highest = -1e9f;
    for (std::size_t i = 0; i < plant.points_m.size(); ++i)
        if (plant.labels[i] == 1) {
            lowest = std::min(lowest, plant.points_m[i].y);
            highest = std::max(highest, plant.points_m[i].y);
            EXPECT_LT(std::hypot(plant.points_m[i].x, plant.points_m[i].z), 0.008f);
        }
    EXPECT_NEAR(lowest, 0.f, 0.003f);
    EXPECT_NEAR(highest, test::kMadeStemHeight_m, 0.005f);
    EXPECT_NEAR(plant.stem().length_m, test::kMadeStemHeight_m, 0.005f);
    for (const test::MadeLeaf& made : test::kMadeLeaves) {
        const PlantOrgan* leaf = plant.organ(made.label);
        ASSERT_NE(leaf, nullptr);
        EXPECT_FALSE(leaf->stem);
        EXPECT_NEAR(leaf->length_m, made.length_m(), kLengthTolerance * made.length_m())
            << "leaf " << made.label;
        EXPECT_NEAR(leaf->maxWidth_m, made.width_m, kWidthTolerance * made.width_m)
            << "leaf " << made.label;
        // It starts where it leaves the stem, at the height it was attached.
        ASSERT_FALSE(leaf->centreLine_m.empty());
        EXPECT_NEAR(leaf->centreLine_m.front().y, made.attach_m, 0.005f) << "leaf " << made.label;
    }
}

TEST(ScannedPlant, BadFilesAreOneClearErrorNamingTheFile) {
    const auto dir = test::freshTempDir("scanned_plant_bad");
    const auto errorOf = [](const std::filesystem::path& file, ScannedPlantOptions options = {}) {
        try {
            (void)loadScannedPlant(file, options);
        } catch (const SynthError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    std::ofstream(dir / "broken.txt") << "1 2 3 1\n4 5 six 1\n";
    EXPECT_NE(errorOf(dir / "broken.txt").find("line 2"), std::string::npos);
    EXPECT_NE(errorOf(dir / "missing.txt").find("missing.txt"), std::string::npos);
    std::ofstream(dir / "one.txt") << "0 0 0 1\n10 0 0 1\n0 10 0 1\n0 0 10 1\n";
    EXPECT_NE(errorOf(dir / "one.txt").find("organ"), std::string::npos);
    const auto made = test::writeMadePlant(dir / "made.txt");
    ScannedPlantOptions metres;
    metres.unit = LengthUnit::Metre;
    const std::string unit = errorOf(made, metres);
    EXPECT_NE(unit.find("--plant-unit"), std::string::npos) << unit;
    std::ofstream(dir / "bare.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                       "property float y\nproperty float z\nend_header\n0 0 0\n"
                                       "1 0 0\n0 1 0\n";
    EXPECT_NE(errorOf(dir / "bare.ply").find("skeleton"), std::string::npos);
    std::ofstream(dir / "garbage.ply") << "ply\nthis is not a header\n";
    EXPECT_NE(errorOf(dir / "garbage.ply").find("garbage.ply"), std::string::npos);
}

TEST(ScannedPlant, Label3DMaizeStemsAreTheOrgansTheAuthorsLabelledFirst) {
    const std::filesystem::path dir = test::sharedDataDir() / "real" / "maize-label3d";
    if (!std::filesystem::exists(dir)) GTEST_SKIP() << "shared data not present: " << dir;
    for (const char* name : {"v-3-1", "v-3-2", "v-6-1", "v-6-2", "v-9-1", "v-12-1"}) {
        const ScannedPlant plant = loadScannedPlant(dir / (std::string(name) + "-l-r.txt"));
        EXPECT_EQ(plant.stemLabel, 1) << name << ": " << plant.stemFoundBy;
        for (const PlantOrgan& o : plant.organs) {
            if (o.stem) continue;
            // No leaf is shorter than the straight line from its base to its farthest point, nor
            // longer than a leaf arching over (as long as 2.5 times that line) allows; beyond its
            // sheath, the centre line runs along the leaf's own points, within half its width (a
            // rolled young leaf's centre lies inside the roll).
            float farthest = 0.f;
            std::vector<glm::vec3> own;
            for (std::size_t i = 0; i < plant.points_m.size(); ++i)
                if (plant.labels[i] == o.label) {
                    own.push_back(plant.points_m[i]);
                    farthest = std::max(farthest,
                                        glm::distance(plant.points_m[i], o.centreLine_m.front()));
                }
            EXPECT_GE(o.length_m, 0.95f * farthest) << name << " leaf " << o.label;
            EXPECT_LE(o.length_m, 2.5f * farthest) << name << " leaf " << o.label;
            float along = 0.f;
            for (std::size_t k = 1; k < o.centreLine_m.size(); ++k) {
                along += glm::distance(o.centreLine_m[k - 1], o.centreLine_m[k]);
                if (along < 0.2f * o.length_m) continue;
                float nearest = 1e9f;
                for (const glm::vec3& p : own)
                    nearest = std::min(nearest, glm::distance(p, o.centreLine_m[k]));
                EXPECT_LT(nearest, std::max(0.015f, 0.6f * o.maxWidth_m))
                    << name << " leaf " << o.label << " at " << along;
            }
            EXPECT_GT(o.maxWidth_m, 0.002f) << name << " leaf " << o.label;
            EXPECT_LT(o.maxWidth_m, 0.15f) << name << " leaf " << o.label;
        }
    }
}

TEST(ScannedPlant, Pheno4DLeavesFollowTheirSkeletonAndItsStemIsOrganZero) {
    const std::filesystem::path dir = test::sharedDataDir() / "real" / "maize-pheno4d-seedling";
    if (!std::filesystem::exists(dir)) GTEST_SKIP() << "shared data not present: " << dir;
    ScannedPlantOptions options;
    options.skeleton = dir / "03-13.graph.txt";
    options.voxel_m = 0.0005f;
    const ScannedPlant plant = loadScannedPlant(dir / "03-13.ply", options);
    EXPECT_EQ(plant.stemLabel, 0);
    ASSERT_EQ(plant.organs.size(), 4u);  // the README: a stem and 3 leaves
    // The README: 03-13's skeleton holds 6 stem nodes and 3 + 3 + 2 leaf nodes.
    std::vector<std::size_t> nodes;
    for (const PlantOrgan& o : plant.organs)
        if (!o.stem) nodes.push_back(o.centreLine_m.size());
    std::sort(nodes.begin(), nodes.end());
    EXPECT_EQ(nodes, (std::vector<std::size_t>{2, 3, 3}));
    for (const PlantOrgan& o : plant.organs) EXPECT_GT(o.length_m, 0.f) << "organ " << o.label;
    EXPECT_NEAR(plant.height_m(), 0.087f, 0.02f);  // about 87 mm tall
}

}  // namespace
}  // namespace meadow::synth
