// Tile instancing on the GPU (Fan & Sheng, Sec. 4.5): blades made from the shared patch stand on
// the terrain, neighbouring tiles turn the patch differently, the density map and the distance
// thin them by threshold, simulated tiles come from the pool and go back once recovered; and in
// images: the far field covers the ground to the horizon, the transition band hides the popping
// of the hand-over, shadows darken the ground behind a prop, and the bundled prairie plants more
// than 10^8 blades in under a gigabyte.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "frame_setup.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/renderer.h"
#include "physics_scene_pass.h"
#include "scene_gpu.h"
#include "support/grass_pixels.h"
#include "tiled_field.h"
#include "tiled_scene.h"

namespace meadow::runtime {
namespace {

using meadow::test::grassShare;

// The passes of one tiled scene without the renderer: the tests look at the buffers.
struct TiledRun {
    SceneDescription scene;
    SceneBlades blades;
    SceneGpu gpu;
    TiledField field;
    gl::Texture depth;  // the culling's depth input (occlusion is off in these scenes)

    TiledRun(GlContext& context, SceneDescription s)
        : scene(std::move(s)),
          blades(buildSceneBlades(scene)),
          gpu(uploadScene(blades, scene)),
          field(context, scene, *blades.terrain, blades.tilePatch),
          depth(gl::Texture::create(GL_TEXTURE_2D)) {
        glTextureStorage2D(depth.id(), 1, GL_DEPTH_COMPONENT32F, 1, 1);
    }

    gpu::FrameGpu frameAt(const CameraPose& pose, float time_s) const {
        return frameGpuOf(scene, pose, time_s, scene.render.width_px, scene.render.height_px);
    }

    // The blades emit() made for this camera.
    std::vector<gpu::BladeGpu> emitted(const CameraPose& pose, float time_s = 0.f) {
        const gpu::FrameGpu frame = frameAt(pose, time_s);
        field.emit(PassInputs{scene, gpu, frame, depth, time_s, 0.f});
        gpu::DrawCommandGpu command{};
        glGetNamedBufferSubData(gpu.drawCommand.id(), 0, sizeof command, &command);
        std::vector<gpu::BladeGpu> out(std::min(command.vertexCount, gpu.bladeCount));
        glGetNamedBufferSubData(gpu.blades.id(), 0,
                                static_cast<GLsizeiptr>(out.size() * sizeof(gpu::BladeGpu)),
                                out.data());
        return out;
    }
};

cv::Mat renderOnce(GlContext& context, const SceneDescription& scene, int frame = 0) {
    Renderer renderer(context, scene);
    cv::Mat image;
    for (int i = 0; i <= frame; ++i) image = renderer.renderFrame(i).image_bgr;
    return image;
}

TEST(TiledFieldGLTest, EmittedBladesStandOnTheTerrainAndNeighbouringTilesTurnThePatch) {
    GlContext context;
    TiledRun run(context, test::tiledScene("tiled_emit"));
    const std::vector<gpu::BladeGpu> blades = run.emitted({{0.f, 1.5f, 6.f}, {0.f, 0.f, 0.f}});
    ASSERT_GT(blades.size(), 1000u);
    float worst = 0.f;
    for (const gpu::BladeGpu& b : blades)
        worst = std::max(
            worst,
            std::abs(b.v0_height.y - run.blades.terrain->heightAt({b.v0_height.x, b.v0_height.z})));
    EXPECT_LT(worst, 0.002f) << "roots off the terrain by up to " << worst << " m";

    // Four neighbouring tiles, every blade of the patch: roots relative to each tile's corner.
    const gpu::FrameGpu frame = run.frameAt({{0.f, 1.5f, 6.f}, {0.f, 0.f, 0.f}}, 0.f);
    const PassInputs in{run.scene, run.gpu, frame, run.depth, 0.f, 0.f};
    std::vector<std::vector<glm::vec2>> roots;
    for (std::uint32_t x : {14u, 15u})
        for (std::uint32_t z : {14u, 15u}) {
            roots.emplace_back();
            for (const gpu::BladeGpu& b : run.field.settledTile({x, z}, in))
                roots.back().push_back(glm::vec2(b.v0_height.x, b.v0_height.z) -
                                       (glm::vec2(-30.f) + 2.f * glm::vec2(x, z)));
        }
    int samePairs = 0;
    for (std::size_t a = 0; a < roots.size(); ++a)
        for (std::size_t b = a + 1; b < roots.size(); ++b) {
            int same = 0;
            for (std::size_t k = 0; k < roots[a].size(); ++k)
                same += glm::length(roots[a][k] - roots[b][k]) < 1e-3f;
            samePairs += same * 2 > static_cast<int>(roots[a].size());
        }
    EXPECT_LT(samePairs, 6) << "every neighbouring tile repeats the patch unturned";
}

TEST(TiledFieldGLTest, TheDensityMapAndTheDistanceThinTheBladesByThreshold) {
    const auto dir = test::freshTestDirectory("tiled_density");
    cv::Mat map(16, 16, CV_8U, cv::Scalar(255));
    map.colRange(0, 8).setTo(0);  // x < 0 bare
    cv::imwrite((dir / "density.png").string(), map);
    nlohmann::json j = test::tiledSceneJson(
        {{"blades",
          {{"density_map",
            {{"image", "density.png"}, {"min_xz_m", {-30, -30}}, {"max_xz_m", {30, 30}}}}}},
         {"culling", {{"orientation", false}, {"frustum", false}}}});
    GlContext context;
    TiledRun run(context, loadSceneDescription(test::writeScene(dir, j)));
    const glm::vec3 camera(2.f, 1.f, 0.f);
    const std::vector<gpu::BladeGpu> blades = run.emitted({camera, {2.f, 0.f, -5.f}});
    ASSERT_GT(blades.size(), 500u);
    // Per square metre of ground, in two half rings about the camera (x > the camera's, all on
    // white): the full density up to 4 m, (4 / d)^2 of it beyond (keptFraction).
    double inner = 0.0, outer = 0.0, bare = 0.0;
    for (const gpu::BladeGpu& b : blades) {
        const glm::vec3 root(b.v0_height);
        if (root.x < -0.5f) ++bare;
        if (root.x < camera.x) continue;
        const float r = glm::length(glm::vec2(root.x - camera.x, root.z - camera.z));
        if (r > 1.5f && r < 3.f) ++inner;
        if (r > 7.f && r < 8.f) ++outer;
    }
    EXPECT_EQ(bare, 0.0) << "blades where the density map is black";
    const double innerDensity = inner / (0.5 * M_PI * (9.0 - 2.25));
    const double outerDensity = outer / (0.5 * M_PI * (64.0 - 49.0));
    const double expected = std::pow(4.0 / std::sqrt(7.5 * 7.5 + 1.0), 2.0);
    EXPECT_NEAR(outerDensity / innerDensity, expected, 0.35 * expected);
    EXPECT_NEAR(innerDensity, static_cast<double>(run.blades.tilePatch.size()) / 4.0, 40.0);
}

TEST(TiledFieldImageGLTest, TheDensityMapLeavesBareGroundWhereItIsBlack) {
    // Seen from above: the black half of the map is soil, the white half grass.
    const auto dir = test::freshTestDirectory("tiled_density_image");
    cv::Mat map(16, 16, CV_8U, cv::Scalar(255));
    map.colRange(0, 8).setTo(0);
    cv::imwrite((dir / "density.png").string(), map);
    const nlohmann::json j = test::tiledSceneJson(
        {{"blades",
          {{"density_map",
            {{"image", "density.png"}, {"min_xz_m", {-30, -30}}, {"max_xz_m", {30, 30}}}}}},
         {"camera", {{"position_m", {0, 4, 0.01}}, {"target_m", {0, 0, 0}}}},
         {"render", {{"size_px", {120, 120}}}}});
    GlContext context;
    const cv::Mat image = renderOnce(context, loadSceneDescription(test::writeScene(dir, j)));
    EXPECT_LT(grassShare(image, cv::Rect(0, 0, 50, 120)), 0.02);
    EXPECT_GT(grassShare(image, cv::Rect(70, 0, 50, 120)), 0.3);
}

TEST(TiledFieldGLTest, SimulatedTilesComeFromThePoolAndGoBackOnceRecovered) {
    // A sphere rolls through the middle of the field and off to a corner; the camera is high up,
    // too far for its own tiles to be simulated.
    nlohmann::json j =
        test::tiledSceneJson({{"physics", {{"enabled", true}}},
                              {"wind",
                               {{"wave_amplitude_m_s", 0.5},
                                {"gust_amplitude_m_s", 0},
                                {"turbulence_amplitude_m_s", 0}}},
                              {"colliders",
                               {{{"radius_m", 0.3},
                                 {"path",
                                  {{{"time_s", 0}, {"position_m", {-3, 0.15, 1}}},
                                   {{"time_s", 1}, {"position_m", {3, 0.15, 1}}},
                                   {{"time_s", 1.2}, {"position_m", {26, 0.15, 26}}}}}}}}});
    GlContext context;
    TiledRun run(context,
                 loadSceneDescription(test::writeScene(test::freshTestDirectory("tiled_pool"), j)));
    const CameraPose high{{0.f, 30.f, 0.1f}, {0.f, 0.f, 0.f}};
    const TileKey crossed{15, 15};  // x, z in [0, 2): the sphere passes over it at t ~ 0.5 s
    const float recovery =
        recoveryTime_s(run.scene.physics.collisionDecay_per_s, run.scene.blades.stiffness.x);
    bool wasSimulated = false;
    float pressedTip = 1e9f, releasedAt = -1.f;
    std::vector<gpu::BladeGpu> lastSimulated, settledThen;
    const float dt = 1.f / 30.f;
    for (int f = 0; f * dt < 1.2f + recovery + 0.3f; ++f) {
        const float t = static_cast<float>(f) * dt;
        const gpu::FrameGpu frame = run.frameAt(high, t);
        const PassInputs in{run.scene, run.gpu, frame, run.depth, t, f == 0 ? 0.f : dt};
        run.field.simulate(in);
        const bool simulated = run.field.pool().slotOf(crossed).has_value();
        if (simulated) {
            wasSimulated = true;
            lastSimulated = run.field.readSimulatedTile(crossed);
            for (const gpu::BladeGpu& b : lastSimulated)
                pressedTip = std::min(pressedTip, b.v2_stiffness.y - b.v0_height.y);
            settledThen = run.field.settledTile(crossed, in);
        } else if (wasSimulated && releasedAt < 0.f) {
            releasedAt = t;
        }
        EXPECT_LE(run.field.pool().activeCount(), 16u);
    }
    ASSERT_TRUE(wasSimulated) << "the tile under the sphere was never simulated";
    EXPECT_LT(pressedTip, 0.05f) << "the sphere pressed no blade of the tile down";
    ASSERT_GT(releasedAt, 0.f) << "the tile was never given back";
    // Not before its blades had time to recover from the last press (the sphere left at ~0.6 s).
    EXPECT_GT(releasedAt, 0.6f + recovery - 0.2f);
    // The frame before release: every blade within 2 cm of where the unsimulated tile draws it.
    ASSERT_EQ(lastSimulated.size(), settledThen.size());
    float worst = 0.f;
    for (std::size_t k = 0; k < lastSimulated.size(); ++k)
        worst = std::max(worst, glm::length(glm::vec3(lastSimulated[k].v2_stiffness) -
                                            glm::vec3(settledThen[k].v2_stiffness)));
    EXPECT_LT(worst, 0.02f) << "a released blade jumps by " << worst << " m";
    // The sphere rests in the far corner, where its own tiles stay simulated.
    EXPECT_GT(run.field.pool().activeCount(), 0u);
}

// Rows of the image where the ground lies between `near_m` and `far_m` ahead of a level camera.
cv::Range groundRows(const gpu::FrameGpu& frame, glm::vec3 camera, float ground_m, float near_m,
                     float far_m, int height_px) {
    const auto row = [&](float d) {
        const glm::vec4 q = frame.clipFromWorld * glm::vec4(camera.x, ground_m, camera.z - d, 1.f);
        return static_cast<int>(
            std::lround((0.5f - 0.5f * q.y / q.w) * static_cast<float>(height_px)));
    };
    return {row(far_m), row(near_m)};
}

TEST(TiledFieldImageGLTest, TheFarFieldCoversTheGroundToTheHorizon) {
    const nlohmann::json flatAndLevel = {
        {"terrain",
         {{"min_xz_m", {-200, -400}}, {"max_xz_m", {200, 20}}, {"samples", 43}, {"relief_m", 0}}},
        {"camera", {{"position_m", {0, 1.7, 0}}, {"target_m", {0, 1.2, -30}}, {"far_m", 2000}}},
        {"render", {{"size_px", {200, 120}}}}};
    GlContext context;
    nlohmann::json without = flatAndLevel;
    without["tiling"] = {{"far_field", false}};
    const SceneDescription withScene = test::tiledScene("far_field_on", flatAndLevel);
    const cv::Mat on = renderOnce(context, withScene);
    const cv::Mat off = renderOnce(context, test::tiledScene("far_field_off", without));
    const gpu::FrameGpu frame =
        frameGpuOf(withScene, {{0.f, 1.7f, 0.f}, {0.f, 1.2f, -30.f}}, 0.f, 200, 120);
    // Beyond the near blades (12 m) out to 300 m.
    const cv::Range rows = groundRows(frame, {0.f, 1.7f, 0.f}, 0.f, 14.f, 300.f, 120);
    ASSERT_GT(rows.size(), 5);
    const cv::Rect band(0, rows.start, 200, rows.size());
    EXPECT_GT(grassShare(on, band), 0.9) << "bare ground between the near blades and the horizon";
    EXPECT_LT(grassShare(off, band), 0.5) << "without the far field the band should show soil";
}

TEST(TiledFieldImageGLTest, TheTransitionBandHidesTheHandOverToTheFarField) {
    // No thinning before the near distance, no wind, a camera creeping forward (1.7 cm a frame).
    // Popping: the mean absolute grey change between adjacent frames of the rows showing the
    // ground 8-16 m away, around the hand-over at 12 m. Most of it is parallax, the same with or
    // without a band; the band must take the hand-over's part away (measured: about 15 %).
    const auto popping = [](double band, const std::string& name) {
        nlohmann::json j = {
            {"tiling", {{"full_density_distance_m", 100}, {"transition_m", band}}},
            {"wind",
             {{"wave_amplitude_m_s", 0},
              {"gust_amplitude_m_s", 0},
              {"turbulence_amplitude_m_s", 0}}},
            {"camera",
             {{"position_m", nullptr},
              {"target_m", nullptr},
              {"path",
               {{{"time_s", 0}, {"position_m", {0, 1.5, 8}}, {"target_m", {0, 0, -10}}},
                {{"time_s", 10}, {"position_m", {0, 1.5, 3}}, {"target_m", {0, 0, -15}}}}}}}};
        const SceneDescription scene = test::tiledScene(name, j);
        const gpu::FrameGpu frame = frameGpuOf(scene, {{0.f, 1.5f, 8.f}, {0.f, 0.f, -10.f}}, 0.f,
                                               scene.render.width_px, scene.render.height_px);
        const auto rowOf = [&](float d) {
            const glm::vec4 q = frame.clipFromWorld * glm::vec4(0.f, 0.f, 8.f - d, 1.f);
            return static_cast<int>((0.5f - 0.5f * q.y / q.w) *
                                    static_cast<float>(scene.render.height_px));
        };
        const cv::Range rows(rowOf(16.f), rowOf(8.f));
        GlContext context;
        Renderer renderer(context, scene);
        double sum = 0.0;
        cv::Mat previous;
        for (int i = 0; i < 8; ++i) {
            cv::Mat grey;
            cv::cvtColor(renderer.renderFrame(i).image_bgr, grey, cv::COLOR_BGR2GRAY);
            grey = grey.rowRange(rows).clone();
            if (!previous.empty())
                sum += cv::norm(grey, previous, cv::NORM_L1) / static_cast<double>(grey.total());
            previous = grey;
        }
        return sum / 7.0;
    };
    const double hard = popping(0.0, "transition_hard"), smooth = popping(4.0, "transition_band");
    EXPECT_LT(smooth, 0.92 * hard) << "popping with the band " << smooth << ", cut hard " << hard
                                   << " (grey levels a pixel a frame)";
}

// The box's shadow from the near cascade (shadows over 12 m of the view) and from the far one
// (over 3 m: the near cascade's box then ends above the ground, the far one holds it).
class TiledShadowImageGLTest : public testing::TestWithParam<float> {};

TEST_P(TiledShadowImageGLTest, ShadowsDarkenTheGroundWhereAPropStands) {
    const auto dir =
        test::freshTestDirectory("tiled_shadows_" + std::to_string(static_cast<int>(GetParam())));
    // A 1 m box at the origin; the light comes from +x, 45 degrees up: its shadow falls on x <
    // -0.5.
    test::writeGltf(dir / "box.gltf",
                    {{-0.5f, 0.f, -0.5f},
                     {0.5f, 0.f, -0.5f},
                     {0.5f, 0.f, 0.5f},
                     {-0.5f, 0.f, 0.5f},
                     {-0.5f, 1.f, -0.5f},
                     {0.5f, 1.f, -0.5f},
                     {0.5f, 1.f, 0.5f},
                     {-0.5f, 1.f, 0.5f}},
                    {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                     1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0});
    const auto scene = [&](bool shadows) {
        nlohmann::json j = test::tiledSceneJson(
            {{"props", {{{"gltf", "box.gltf"}}}},
             {"terrain", {{"relief_m", 0}}},
             {"blades", {{"density_per_m2", 40}}},
             {"light", {{"direction", {1, 1, 0}}}},
             {"shadows", {{"enabled", shadows}, {"map_size_px", 512}, {"distance_m", GetParam()}}},
             {"camera", {{"position_m", {0, 9, 0.01}}, {"target_m", {0, 0, 0}}}},
             {"render", {{"size_px", {160, 160}}}}});
        return loadSceneDescription(test::writeScene(dir, j));
    };
    GlContext context;
    const SceneDescription lit = scene(true);
    const cv::Mat on = renderOnce(context, lit), off = renderOnce(context, scene(false));
    const gpu::FrameGpu frame =
        frameGpuOf(lit, {{0.f, 9.f, 0.01f}, {0.f, 0.f, 0.f}}, 0.f, 160, 160);
    const auto pixel = [&](float x, float z) {
        const glm::vec4 q = frame.clipFromWorld * glm::vec4(x, 0.f, z, 1.f);
        return cv::Point(static_cast<int>((0.5f + 0.5f * q.x / q.w) * 160.f),
                         static_cast<int>((0.5f - 0.5f * q.y / q.w) * 160.f));
    };
    const auto meanGrey = [&](const cv::Mat& image, float x0, float x1) {
        cv::Mat grey;
        cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
        const cv::Rect area(pixel(x0, -0.3f), pixel(x1, 0.3f));
        return cv::mean(grey(area))[0];
    };
    // Behind the box (x in [-1.4, -0.7]) and well clear of it (x in [2, 3]).
    EXPECT_LT(meanGrey(on, -1.4f, -0.7f), 0.8 * meanGrey(off, -1.4f, -0.7f));
    EXPECT_GT(meanGrey(on, 2.f, 3.f), 0.85 * meanGrey(off, 2.f, 3.f));
}

INSTANTIATE_TEST_SUITE_P(NearAndFarCascade, TiledShadowImageGLTest, testing::Values(12.f, 3.f));

TEST(TiledFieldImageGLTest, TheBundledPrairiePlantsOverAHundredMillionBladesInUnderAGigabyte) {
    SceneDescription prairie =
        loadSceneDescription(MEADOW_SOURCE_DIR "/samples/prairie/prairie.json");
    prairie.render.width_px = 160;
    prairie.render.height_px = 90;
    GlContext context;
    Renderer renderer(context, prairie);
    EXPECT_GE(renderer.bladeCount(), 100'000'000u);
    EXPECT_LT(renderer.gpuMemoryBytes(), std::size_t{1} << 30);
    const RenderedFrame frame = renderer.renderFrame(0);
    EXPECT_GT(frame.stats.bladesDrawn, 1000u);
    EXPECT_GT(grassShare(frame.image_bgr, cv::Rect(0, 45, 160, 45)), 0.5);
}

}  // namespace
}  // namespace meadow::runtime
