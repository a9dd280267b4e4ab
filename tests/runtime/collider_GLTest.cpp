// Colliders seen and felt: a sphere collider moving along its path is drawn where it is at each
// frame, a hidden one is not drawn, and a mesh collider (a capsule, packed into spheres) rolled
// across a patch of grass presses the blades under its path and no others.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/core.hpp>

#include "collider_shapes.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

// Pixels further than this from the sky colour (max over B, G, R) show something.
constexpr int kSkyDistance = 40;

struct Blob {
    int pixels = 0;
    double meanX = 0.0;
};
Blob nonSky(const cv::Mat& image) {
    const cv::Vec3b sky = image.at<cv::Vec3b>(0, 0);
    Blob b;
    for (int y = 0; y < image.rows; ++y)
        for (int x = 0; x < image.cols; ++x)
            if (cv::norm(image.at<cv::Vec3b>(y, x), sky, cv::NORM_INF) > kSkyDistance)
                ++b.pixels, b.meanX += x;
    if (b.pixels) b.meanX /= b.pixels;
    return b;
}

// A camera 3 m from the origin looking along -Z, a 10 cm ground square far below the view, and
// `colliders`; 160 x 120 px, 30 frames a second.
SceneDescription colliderScene(const std::string& name, const nlohmann::json& colliders) {
    const auto dir = test::freshTestDirectory(name);
    test::writeQuad(dir / "ground.gltf", -0.05f, 0.05f, -0.05f, 0.05f, -50.f);
    const TriangleMesh capsule = sphereMesh(0.2f, 12, 24);
    std::vector<glm::vec3> positions = capsule.positions_m;
    for (glm::vec3& p : positions) p.x += p.x >= 0.f ? 0.3f : -0.3f;  // a capsule along X
    std::vector<std::uint32_t> indices;
    for (const glm::uvec3& t : capsule.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
    test::writeGltf(dir / "capsule.gltf", positions, indices);
    const nlohmann::json extra = {
        {"blades", {{"density_per_m2", 100000}}},
        {"camera", {{"position_m", {0, 0, 3}}, {"target_m", {0, 0, 0}}, {"vertical_fov_deg", 50}}},
        {"light", {{"sky_color", {0.2, 0.4, 0.9}}}},
        {"colliders", colliders},
        {"render", {{"size_px", {160, 120}}, {"msaa_samples", 1}, {"patch_size", 64}}}};
    return loadSceneDescription(test::writeScene(dir, test::minimalScene("ground.gltf", extra)));
}

TEST(ColliderGLTest, AMovingColliderIsDrawnWhereItIsAndAHiddenOneIsNot) {
    GlContext context;
    const nlohmann::json moving = {{"radius_m", 0.25},
                                   {"path",
                                    {{{"time_s", 0}, {"position_m", {-0.8, 0, 0}}},
                                     {{"time_s", 1}, {"position_m", {0.8, 0, 0}}}}}};
    const SceneDescription scene = colliderScene("collider_drawn", nlohmann::json::array({moving}));
    Renderer renderer(context, scene);
    std::vector<Blob> seen;
    renderer.renderFrames(0, 31, true, [&](RenderedFrame&& f) {
        if (f.stats.frame == 0 || f.stats.frame == 15 || f.stats.frame == 30)
            seen.push_back(nonSky(f.image_bgr));
    });
    ASSERT_EQ(seen.size(), 3u);
    // 3 m away with a 50 deg view, 1 m spans 120 / (2 tan 25 deg * 3) = 42.9 px.
    const double pxPerM = 120.0 / (2.0 * std::tan(glm::radians(25.0)) * 3.0);
    const double expected[3] = {80.0 - 0.8 * pxPerM, 80.0, 80.0 + 0.8 * pxPerM};
    for (int k = 0; k < 3; ++k) {
        // A 0.25 m ball: pi (0.25 * 42.9)^2 = 361 px, give or take its silhouette's pixels.
        EXPECT_NEAR(seen[k].pixels, 361, 60) << "frame " << 15 * k;
        EXPECT_NEAR(seen[k].meanX, expected[k], 1.5) << "frame " << 15 * k;
    }

    nlohmann::json hidden = moving;
    hidden["visible"] = false;
    Renderer hiddenRenderer(context,
                            colliderScene("collider_hidden", nlohmann::json::array({hidden})));
    EXPECT_EQ(nonSky(hiddenRenderer.renderFrame(15).image_bgr).pixels, 0);

    const nlohmann::json mesh = {{"gltf", "capsule.gltf"}, {"center_m", {0, 0, 0}}};
    Renderer meshRenderer(context, colliderScene("collider_mesh", nlohmann::json::array({mesh})));
    const Blob capsule = nonSky(meshRenderer.renderFrame(0).image_bgr);
    // The capsule's silhouette: a 0.6 x 0.4 m rectangle with two half discs, 0.366 m^2.
    EXPECT_NEAR(capsule.pixels, (0.6 * 0.4 + 3.14159 * 0.04) * pxPerM * pxPerM, 80.0);
    EXPECT_NEAR(capsule.meanX, 80.0, 1.5);
}

}  // namespace
}  // namespace meadow::runtime
