// Tile instancing on the CPU: the terrain's height field, the tiles near and in view, the pool
// of simulated tiles, the shared patch, the far field's slices, and the scene file's checks.
#include "tile_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/core.hpp>

#include "far_field.h"
#include "meadow/runtime/error.h"
#include "tile_patch.h"
#include "tiled_scene.h"

namespace meadow::runtime {
namespace {

TerrainDescription hills() {
    TerrainDescription t;
    t.minXZ_m = {-100.f, -50.f};
    t.maxXZ_m = {100.f, 50.f};
    t.samples = 101;
    t.relief_m = 8.f;
    t.featureSize_m = 60.f;
    t.seed = 4;
    return t;
}

TEST(HeightField, SpansTheReliefAndIsTheSameForASeed) {
    const HeightField a = makeHeightField(hills()), b = makeHeightField(hills());
    double lo = 0.0, hi = 0.0;
    cv::minMaxLoc(a.height_m, &lo, &hi);
    EXPECT_NEAR(lo, 0.0, 1e-4);
    EXPECT_NEAR(hi, 8.0, 1e-3);
    EXPECT_EQ(cv::norm(a.height_m, b.height_m, cv::NORM_INF), 0.0);
    TerrainDescription other = hills();
    other.seed = 5;
    EXPECT_GT(cv::norm(a.height_m, makeHeightField(other).height_m, cv::NORM_INF), 0.5);
}

TEST(HeightField, HeightAtAgreesWithTheGridAndTheMesh) {
    const HeightField f = makeHeightField(hills());
    const glm::vec2 d = f.spacing_m();
    EXPECT_NEAR(d.x, 2.f, 1e-5f);
    EXPECT_FLOAT_EQ(f.heightAt(f.minXZ_m + glm::vec2(3 * d.x, 7 * d.y)),
                    f.height_m.at<float>(7, 3));
    const TriangleMesh mesh = terrainMesh(f);
    ASSERT_EQ(mesh.positions_m.size(), 101u * 101u);
    EXPECT_EQ(mesh.triangles.size(), 2u * 100u * 100u);
    for (std::size_t i = 0; i < mesh.positions_m.size(); i += 97) {
        const glm::vec3 p = mesh.positions_m[i];
        EXPECT_NEAR(f.heightAt({p.x, p.z}), p.y, 1e-4f);
        EXPECT_GT(mesh.normals[i].y, 0.5f);  // gentle hills: normals point up
    }
}

TEST(TileGrid, BoxesHoldTheGroundAndTheBladesAndNearestComeFirst) {
    const HeightField f = makeHeightField(hills());
    const TileGrid grid(f, 4.f, 0.5f);
    EXPECT_EQ(grid.tilesX(), 50);
    EXPECT_EQ(grid.tilesZ(), 25);
    glm::vec3 lo, hi;
    grid.boxOf({10, 5}, lo, hi);
    for (float x = 0.f; x <= 4.f; x += 0.5f)
        for (float z = 0.f; z <= 4.f; z += 0.5f) {
            const float h = f.heightAt(f.minXZ_m + glm::vec2(40.f + x, 20.f + z));
            EXPECT_GE(h, lo.y + 0.5f - 1e-4f);
            EXPECT_LE(h, hi.y - 0.5f + 1e-4f);
        }
    const glm::vec3 p(-58.f, f.heightAt({-58.f, -28.f}) + 1.f, -28.f);
    const std::vector<TileKey> near = grid.tilesNear(p, 6.f);
    ASSERT_FALSE(near.empty());
    EXPECT_EQ(near.front(), (TileKey{10, 5}));  // the tile under the point
    for (std::size_t i = 1; i < near.size(); ++i)
        EXPECT_LE(grid.distanceTo(near[i - 1], p), grid.distanceTo(near[i], p) + 1e-5f);
    for (TileKey t : near) EXPECT_LE(grid.distanceTo(t, p), 6.f);
}

TEST(TileGrid, TilesBehindTheCameraAreNotInView) {
    TerrainDescription flat = hills();
    flat.relief_m = 0.f;
    const TileGrid grid(makeHeightField(flat), 4.f, 0.5f);
    const glm::vec3 camera(0.f, 2.f, 0.f);
    const glm::mat4 clip = glm::perspective(glm::radians(50.f), 16.f / 9.f, 0.05f, 500.f) *
                           glm::lookAt(camera, glm::vec3(0.f, 0.f, -10.f), {0.f, 1.f, 0.f});
    const std::vector<TileKey> all = grid.tilesNear(camera, 30.f);
    const std::vector<TileKey> seen = grid.tilesInView(camera, clip, 30.f);
    EXPECT_LT(seen.size(), all.size() / 2);
    EXPECT_GT(seen.size(), all.size() / 8);
    for (TileKey t : seen) {
        glm::vec3 lo, hi;
        grid.boxOf(t, lo, hi);
        EXPECT_LT(lo.z, camera.z + 1e-3f) << "a tile wholly behind the camera";
    }
}

TEST(TilePool, SlotsAreGivenWhenNeededAndTakenBackOnceRecovered) {
    TilePool pool(2, 1.5f);
    const TileKey a{1, 1}, b{2, 1}, c{3, 1};
    TilePool::Update u = pool.update({a, b, c}, 0.f);
    ASSERT_EQ(u.activated.size(), 2u);
    EXPECT_EQ(u.refused, 1u);  // the pool is full: c is drawn unsimulated
    EXPECT_EQ(*pool.slotOf(a), 0u);
    EXPECT_EQ(*pool.slotOf(b), 1u);
    EXPECT_FALSE(pool.slotOf(c));
    EXPECT_EQ(pool.slotsInUse(), 2u);
    // a stays needed; b, last needed at 0 s, is kept until it has had time to recover (1.5 s).
    u = pool.update({a}, 1.f);
    EXPECT_TRUE(u.released.empty());
    u = pool.update({a}, 1.4f);
    EXPECT_TRUE(u.released.empty());
    u = pool.update({a}, 1.6f);
    ASSERT_EQ(u.released.size(), 1u);
    EXPECT_EQ(u.released.front(), b);
    EXPECT_EQ(pool.activeCount(), 1u);
    u = pool.update({a, c}, 3.f);
    ASSERT_EQ(u.activated.size(), 1u);
    EXPECT_EQ(u.activated.front().second, 1u);  // b's slot, reused
}

TEST(TilePool, RecoveryTimeCountsTheCollisionStrengthAndTheStiffness) {
    EXPECT_NEAR(recoveryTime_s(0.5f, 12.f), 2.f + std::log(1000.f) / 12.f, 1e-5f);
    EXPECT_NEAR(recoveryTime_s(0.f, 10.f), std::log(1000.f) / 10.f, 1e-5f);
}

TEST(TilePatch, HoldsTheSceneDensityOnOneTileWithThresholdsSpread) {
    const SceneDescription scene = test::tiledScene("tile_patch");
    const std::vector<gpu::TileInstanceGpu> patch = buildTilePatch(scene);
    EXPECT_EQ(patch.size() % BLADE_WORKGROUP_SIZE, 0u);
    EXPECT_NEAR(static_cast<double>(patch.size()), 150.0 * 4.0, 64.0);
    double thresholds = 0.0;
    for (const gpu::TileInstanceGpu& g : patch) {
        EXPECT_GE(g.place.x, 0.f);
        EXPECT_LT(g.place.x, 2.f);
        EXPECT_GE(g.place.z, 0.f);
        EXPECT_LT(g.place.z, 2.f);
        EXPECT_GT(g.restV2_height.y, 0.f);  // tips above the root
        EXPECT_GT(g.restV2_height.w, 0.f);
        thresholds += g.look.z;
    }
    EXPECT_NEAR(thresholds / static_cast<double>(patch.size()), 0.5, 0.05);
    EXPECT_GT(tallestBlade_m(patch), 0.1f);
}

TEST(FarFieldSlices, DrawThePatchSideOnDenserAtTheRootThanAtTheTips) {
    const SceneDescription scene = test::tiledScene("far_field_slices");
    const std::vector<gpu::TileInstanceGpu> patch = buildTilePatch(scene);
    const FarFieldSlices s = buildFarFieldSlices(patch, scene, 8, 256, 32);
    ASSERT_EQ(s.layers.size(), 16u);
    EXPECT_FLOAT_EQ(s.spacing_m, 0.25f);
    EXPECT_NEAR(s.height_m, tallestBlade_m(patch), 0.2f);
    double coverage = 0.0;
    for (float c : s.bandCoverage) coverage += c / FarFieldSlices::kHeightBands;
    EXPECT_GT(coverage, 0.05);
    EXPECT_LT(coverage, 0.9);
    double bottom = 0.0, top = 0.0;
    for (const cv::Mat& layer : s.layers) {
        std::vector<cv::Mat> channels;
        cv::split(layer, channels);
        bottom += cv::mean(channels[3].rowRange(0, 8))[0];
        top += cv::mean(channels[3].rowRange(24, 32))[0];
    }
    EXPECT_GT(bottom, 2.0 * top);  // blades taper and lean: fewer reach the top
    // Band albedos lie between the root's and the tip's colours (times the hue variation and
    // the root's occlusion), darker at the ground than at the top.
    EXPECT_GT(s.bandAlbedo[0].g, scene.render.rootColor.g * scene.render.aoAtRoot * 0.7f);
    EXPECT_LT(s.bandAlbedo[7].g, scene.render.tipColor.g * 1.3f);
    EXPECT_LT(s.bandAlbedo[0].g, s.bandAlbedo[7].g);
    EXPECT_GT(s.bandCoverage[0], s.bandCoverage[7]);
}

TEST(TiledSceneFile, TilingNeedsATerrainAndNoGrassMesh) {
    const auto dir = test::freshTestDirectory("tiled_scene_errors");
    const auto errorOf = [&](const nlohmann::json& j) -> std::string {
        try {
            loadSceneDescription(test::writeScene(dir, j));
        } catch (const RuntimeError& e) {
            return e.what();
        }
        return "";
    };
    EXPECT_EQ(errorOf(test::tiledSceneJson()), "");
    nlohmann::json noTerrain = test::tiledSceneJson();
    noTerrain.erase("terrain");
    EXPECT_NE(errorOf(noTerrain).find("add a \"terrain\" section"), std::string::npos);
    nlohmann::json noTiling = test::tiledSceneJson();
    noTiling.erase("tiling");
    EXPECT_NE(errorOf(noTiling).find("add a \"tiling\" section"), std::string::npos);
    nlohmann::json wideBand = test::tiledSceneJson({{"tiling", {{"transition_m", 20}}}});
    EXPECT_NE(errorOf(wideBand).find("transition_m"), std::string::npos);
    nlohmann::json hugeTerrain = test::tiledSceneJson({{"terrain", {{"samples", 100000}}}});
    EXPECT_NE(errorOf(hugeTerrain).find("samples"), std::string::npos);
}

}  // namespace
}  // namespace meadow::runtime
