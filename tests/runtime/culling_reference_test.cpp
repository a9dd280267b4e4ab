// The CPU reference of the per-blade culling (Jahrmann & Wimmer 2017, Sec. 5.2), which compiles
// shaders/common_culling.glsl as C++; culling_pass_GLTest.cpp holds the GPU pass against it.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "culling_test_scene.h"

namespace meadow::runtime {
namespace {

gpu::BladeGpu uprightBlade(glm::vec3 v0, float h, float angle) {
    const glm::vec3 up{0.f, 1.f, 0.f};
    return {glm::vec4(v0, h), glm::vec4(v0 + h * up, 0.01f), glm::vec4(v0 + h * up, 10.f),
            glm::vec4(up, angle)};
}

gpu::PatchGpu patchOf(std::uint32_t first, std::uint32_t count, glm::vec3 lo, glm::vec3 hi) {
    return {glm::vec4(lo, 0.f), glm::vec4(hi, 0.f), glm::uvec4(first, count, 0, 0)};
}

struct Camera {
    glm::vec3 position{0.f, 1.f, 5.f};
    glm::mat4 clipFromWorld =
        glm::perspective(glm::radians(60.f), 1.f, 0.1f, 100.f) *
        glm::lookAt(glm::vec3(0.f, 1.f, 5.f), glm::vec3(0.f, 1.f, 0.f), glm::vec3(0.f, 1.f, 0.f));
};

CullSettings only(bool orientation, bool frustum, bool distance, bool occlusion) {
    CullSettings s;
    s.orientation = orientation;
    s.frustum = frustum;
    s.distance = distance;
    s.occlusion = occlusion;
    return s;
}

TEST(CullingReference, SharedHeadersGiveDistinctUniformBindingsAndOneBitPerTest) {
    // physics_params.h and cull_params.h add uniform blocks next to blade_types.h's frame block.
    EXPECT_NE(PHYSICS_UBO_BINDING, FRAME_UBO_BINDING);
    EXPECT_NE(CULL_UBO_BINDING, FRAME_UBO_BINDING);
    EXPECT_NE(CULL_UBO_BINDING, PHYSICS_UBO_BINDING);
    EXPECT_EQ(CULL_TEST_ALL,
              CULL_TEST_ORIENTATION | CULL_TEST_FRUSTUM | CULL_TEST_DISTANCE | CULL_TEST_OCCLUSION);
    for (unsigned bit :
         {CULL_TEST_ORIENTATION, CULL_TEST_FRUSTUM, CULL_TEST_DISTANCE, CULL_TEST_OCCLUSION})
        EXPECT_EQ(bit & (bit - 1), 0u) << bit << " is not a single bit";
    EXPECT_NE(PHYSICS_LENGTH_EXACT, PHYSICS_LENGTH_PAPER);
}

TEST(CullingReference, BladeSeenEdgeOnIsCulledByOrientationAndFaceOnIsKept) {
    const Camera cam;
    // Width direction at angle 0 is +x for up = +y (bladeWidthAxis); the camera looks along -z from
    // +z. A blade at x = 3 seen from the camera: direction (3, 0, -5)/|.|, |dot with +x| = 0.51.
    std::vector<gpu::BladeGpu> blades = {uprightBlade({0.f, 0.f, 0.f}, 0.5f, 0.f),
                                         uprightBlade({0.f, 0.f, 0.f}, 0.5f, 1.5707963f)};
    std::vector<gpu::PatchGpu> patches = {patchOf(0, 2, {-1, 0, -1}, {1, 1, 1})};
    const auto params = packCullParams(only(true, false, false, false), cam.clipFromWorld,
                                       cam.position, 0.1f, 100.f, 1, 0, 0);
    // Blade 0 faces the camera (width along x, viewed along -z); blade 1's width is along -z.
    const CullResult r = cullReference(blades, patches, params, nullptr);
    EXPECT_EQ(r.stats.culledOrientation, 1u);
    ASSERT_EQ(r.visible.size(), 1u);
    EXPECT_EQ(r.visible[0], 0u);
}

TEST(CullingReference, BladeBehindTheCameraIsFrustumCulledAndOneInFrontIsKept) {
    const Camera cam;
    std::vector<gpu::BladeGpu> blades = {uprightBlade({0.f, 0.f, 0.f}, 0.5f, 0.f),
                                         uprightBlade({0.f, 0.f, 10.f}, 0.5f, 0.f)};
    // A patch box spanning both, so only the per-blade test decides.
    std::vector<gpu::PatchGpu> patches = {patchOf(0, 2, {-1, 0, -1}, {1, 1, 11})};
    const auto params = packCullParams(only(false, true, false, false), cam.clipFromWorld,
                                       cam.position, 0.1f, 100.f, 1, 0, 0);
    const CullResult r = cullReference(blades, patches, params, nullptr);
    EXPECT_EQ(r.stats.culledFrustum, 1u);
    EXPECT_EQ(r.visible, std::vector<std::uint32_t>{0u});
}

TEST(CullingReference, PatchOutsideTheFrustumCountsAllItsBladesAsFrustumCulled) {
    const Camera cam;
    std::vector<gpu::BladeGpu> blades(10, uprightBlade({0.f, 0.f, 10.f}, 0.5f, 0.f));
    std::vector<gpu::PatchGpu> patches = {patchOf(0, 10, {-1, 0, 9}, {1, 1, 11})};
    const auto params =
        packCullParams(CullSettings{}, cam.clipFromWorld, cam.position, 0.1f, 100.f, 1, 0, 0);
    const CullResult r = cullReference(blades, patches, params, nullptr);
    EXPECT_EQ(r.stats.culledFrustum, 10u);
    EXPECT_TRUE(r.visible.empty());
}

TEST(CullingReference, DistanceLevelsKeepNMinusKOfEveryNBladesAndNoneBeyondDMax) {
    // Eq. (15) with n = 4, d_max = 20 m: at d_proj = 10 m, floor(4 * 0.5) = 2 keeps id mod 4 <= 2.
    CullSettings s = only(false, false, true, false);
    s.distanceLevels = 4;
    s.maxDistance_m = 20.f;
    const glm::vec3 camera{0.f, 50.f, 0.f};  // high above: d_proj ignores the height along up
    std::vector<gpu::BladeGpu> blades;
    for (int i = 0; i < 40; ++i) blades.push_back(uprightBlade({10.f, 0.f, 0.f}, 0.5f, 0.f));
    for (int i = 0; i < 8; ++i) blades.push_back(uprightBlade({25.f, 0.f, 0.f}, 0.5f, 0.f));
    std::vector<gpu::PatchGpu> patches = {patchOf(0, 40, {9, 0, -1}, {11, 1, 1}),
                                          patchOf(40, 8, {24, 0, -1}, {26, 1, 1})};
    const auto params = packCullParams(s, glm::mat4(1.f), camera, 0.1f, 100.f, 2, 0, 0);
    const CullResult r = cullReference(blades, patches, params, nullptr);
    EXPECT_EQ(r.visible.size(), 30u);  // 3 of every 4 of the near patch, none of the far one
    EXPECT_EQ(r.stats.culledDistance, 10u + 8u);
    for (std::uint32_t i : r.visible) EXPECT_LE(i % 4, 2u) << "blade " << i;
}

TEST(CullingReference, BladesBehindTheOpaqueWallAreOcclusionCulledOthersKept) {
    const testing::CullScene scene = testing::makeCullScene(11);
    CullSettings s = only(false, false, false, true);
    s.occlusionBias_m = 0.05f;
    const auto params = packCullParams(
        s, scene.clipFromWorld, scene.camera_m, scene.near_m, scene.far_m,
        static_cast<std::uint32_t>(scene.patches.size()), scene.depthWidth, scene.depthHeight);
    const DepthImageView depth{scene.depthWidth, scene.depthHeight, scene.depth};
    const CullResult r = cullReference(scene.blades, scene.patches, params, &depth);
    EXPECT_GT(r.stats.culledOcclusion, 100u);
    // Every culled blade is in the right third of the image and more than 6 m from the camera.
    std::vector<bool> visible(scene.blades.size(), false);
    for (std::uint32_t i : r.visible) visible[i] = true;
    for (std::size_t i = 0; i < scene.blades.size(); ++i) {
        if (visible[i]) continue;
        const glm::vec4 q =
            scene.clipFromWorld * glm::vec4(glm::vec3(scene.blades[i].v0_height), 1.f);
        EXPECT_GT(q.x / q.w, 1.f / 3.f - 0.1f) << "blade " << i;
        EXPECT_GT(glm::distance(glm::vec3(scene.blades[i].v0_height), scene.camera_m), 6.f)
            << "blade " << i;
    }
}

TEST(CullingReference, EveryBladeIsCountedOnceVisibleOrCulledByExactlyOneTest) {
    const testing::CullScene scene = testing::makeCullScene(12);
    CullSettings s;
    s.maxDistance_m = 30.f;
    const auto params = packCullParams(
        s, scene.clipFromWorld, scene.camera_m, scene.near_m, scene.far_m,
        static_cast<std::uint32_t>(scene.patches.size()), scene.depthWidth, scene.depthHeight);
    const DepthImageView depth{scene.depthWidth, scene.depthHeight, scene.depth};
    const CullResult r = cullReference(scene.blades, scene.patches, params, &depth);
    const auto& st = r.stats;
    EXPECT_EQ(r.visible.size() + st.culledOrientation + st.culledFrustum + st.culledDistance +
                  st.culledOcclusion,
              scene.blades.size());
    EXPECT_GT(st.culledOrientation, 0u);
    EXPECT_GT(st.culledFrustum, 0u);
    EXPECT_GT(st.culledDistance, 0u);
    EXPECT_GT(st.culledOcclusion, 0u);
    EXPECT_GT(r.visible.size(), 0u);
}

TEST(CullingReference, OcclusionWithoutAMatchingDepthImageIsRejected) {
    const Camera cam;
    std::vector<gpu::BladeGpu> blades = {uprightBlade({0.f, 0.f, 0.f}, 0.5f, 0.f)};
    std::vector<gpu::PatchGpu> patches = {patchOf(0, 1, {-1, 0, -1}, {1, 1, 1})};
    const auto params =
        packCullParams(CullSettings{}, cam.clipFromWorld, cam.position, 0.1f, 100.f, 1, 8, 8);
    EXPECT_THROW((void)cullReference(blades, patches, params, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace meadow::runtime
