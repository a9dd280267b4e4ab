// The meadow in motion, on the CPU reference of the physics (the GPU pass is held to it by
// PhysicsPassGLTest): the bundled scene's blades stand and sway in its wind for seconds, and
// blades pressed flat by a passing collider recover. Tip height: the tip's height above its root
// along the surface normal, against the rest pose's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <vector>

#include "meadow/runtime/scene.h"
#include "physics_reference.h"
#include "physics_scene_pass.h"
#include "scene_gpu.h"

namespace meadow::runtime {
namespace {

constexpr float kFrame_s = 1.f / 30.f;

float tipHeight(const gpu::BladeGpu& b, const glm::vec3& tip) {
    return glm::dot(tip - glm::vec3(b.v0_height), glm::vec3(b.up_direction));
}

float tipHeight(const gpu::BladeGpu& b) { return tipHeight(b, glm::vec3(b.v2_stiffness)); }

float restTipHeight(const gpu::BladeGpu& b, const gpu::BladeRestGpu& r) {
    return tipHeight(b, glm::vec3(r.restV2_eta));
}

// Steps `blades` through one frame of simulated time as the physics pass does (substeps for
// stiff blades), under the scene's settings and `spheres`.
void stepFrame(SceneBlades& blades, const SceneDescription& scene, float time_s,
               const std::vector<CollisionSphere>& spheres) {
    gpu::FrameGpu frame{};
    frame.wind = glm::vec4(scene.wind.direction, scene.wind.waveAmplitude_m_s);
    const PhysicsSettings settings = physicsSettingsOf(scene, frame);
    const PhysicsSubsteps steps = physicsSubsteps(scene.blades.stiffness.y, kFrame_s);
    const auto colliders = packColliders(spheres);
    for (int k = 1; k <= steps.count; ++k)
        physicsStepReference(
            blades.blades, blades.rests, colliders,
            packPhysicsParams(settings, steps.step_s,
                              time_s - kFrame_s + static_cast<float>(k) * steps.step_s,
                              static_cast<std::uint32_t>(blades.blades.size()),
                              static_cast<std::uint32_t>(colliders.size())));
}

SceneDescription bundledScene() {
    return loadSceneDescription(std::filesystem::path(MEADOW_SOURCE_DIR) / "samples" / "scenes" /
                                "meadow.json");
}

// Done when: after 5 s of the bundled scene with its wind, the mean tip height is at least 80 %
// of the rest height; and the wind must move the blades, not leave them still.
TEST(MeadowMotion, TheBundledMeadowStandsAndSwaysInItsWindForFiveSeconds) {
    const SceneDescription scene = bundledScene();
    SceneBlades blades = buildSceneBlades(scene);
    const std::vector<gpu::BladeGpu> rest = blades.blades;
    double restSum = 0.0;
    for (std::size_t i = 0; i < rest.size(); ++i)
        restSum += restTipHeight(rest[i], blades.rests[i]);
    std::vector<glm::vec3> previous(rest.size());
    for (std::size_t i = 0; i < rest.size(); ++i) previous[i] = glm::vec3(rest[i].v2_stiffness);
    double lowest = 1.0, travel_m = 0.0;
    constexpr int kFrames = 150;  // 5 s
    for (int f = 1; f <= kFrames; ++f) {
        stepFrame(blades, scene, static_cast<float>(f) * kFrame_s, {});
        double sum = 0.0;
        for (std::size_t i = 0; i < rest.size(); ++i) {
            sum += tipHeight(blades.blades[i]);
            const glm::vec3 tip = glm::vec3(blades.blades[i].v2_stiffness);
            travel_m += glm::distance(tip, previous[i]);
            previous[i] = tip;
        }
        lowest = std::min(lowest, sum / restSum);
    }
    const double meanTravel_m = travel_m / static_cast<double>(rest.size());
    EXPECT_GE(lowest, 0.8) << "the meadow's mean tip height fell to " << lowest << " of rest";
    // Swaying: over 5 s each tip travels several centimetres back and forth.
    EXPECT_GE(meanTravel_m, 0.03) << "mean tip travel " << meanTravel_m << " m in 5 s";
}

// Done when: after a collider passes, blades recover to at least 90 % within 3 s. A sphere
// rolls over a strip of the meadow and away; the blades it pressed below half their height
// stand again 3 s after it has left.
TEST(MeadowMotion, BladesPressedFlatByAPassingColliderRecoverWithinThreeSeconds) {
    SceneDescription scene = bundledScene();
    scene.wind.waveAmplitude_m_s = 0.f;  // the collider alone
    scene.wind.gustAmplitude_m_s = scene.wind.turbulenceAmplitude_m_s = 0.f;
    SceneBlades blades = buildSceneBlades(scene);
    const std::size_t n = blades.blades.size();
    std::vector<float> restHeight(n);
    for (std::size_t i = 0; i < n; ++i)
        restHeight[i] = restTipHeight(blades.blades[i], blades.rests[i]);
    std::vector<char> pressed(n, 0);
    // A 0.35 m sphere, centre 0.25 m above the ground at z = 0, rolling from x = -2 m to +2 m at
    // 2 m/s, then gone.
    constexpr float kSpeed_mps = 2.f, kStart_m = -2.f, kEnd_m = 2.f;
    const int passFrames = static_cast<int>((kEnd_m - kStart_m) / kSpeed_mps / kFrame_s);
    int f = 1;
    for (; f <= passFrames; ++f) {
        const float x = kStart_m + kSpeed_mps * static_cast<float>(f) * kFrame_s;
        const float ground = 0.f;  // the terrain is near y = 0 there (tested below)
        stepFrame(blades, scene, static_cast<float>(f) * kFrame_s,
                  {{glm::vec3(x, ground + 0.25f, 0.f), 0.35f}});
        for (std::size_t i = 0; i < n; ++i)
            if (tipHeight(blades.blades[i]) < 0.5f * restHeight[i]) pressed[i] = 1;
    }
    const int pressedCount = static_cast<int>(std::count(pressed.begin(), pressed.end(), 1));
    ASSERT_GE(pressedCount, 50) << "the collider must press blades flat to test their recovery";
    constexpr int kRecoveryFrames = 90;  // 3 s
    for (int k = 0; k < kRecoveryFrames; ++k, ++f)
        stepFrame(blades, scene, static_cast<float>(f) * kFrame_s, {});
    double sum = 0.0, restSum = 0.0;
    int low = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (!pressed[i]) continue;
        sum += tipHeight(blades.blades[i]);
        restSum += restHeight[i];
        low += tipHeight(blades.blades[i]) < 0.9f * restHeight[i];
    }
    EXPECT_GE(sum / restSum, 0.9) << pressedCount << " blades pressed";
    EXPECT_LE(low, pressedCount / 10) << "blades still under 90 % of their height";
}

// The bundled scene's roller, a mesh collider packed into spheres, rolls along its path: after
// 3 s, where it is at x = 0, the blades it has just rolled over (0.2-0.6 m behind it, within its
// length) lie pressed, and blades a metre to either side of its path stand as before.
TEST(MeadowMotion, TheBundledRollerLeavesATrailWhereItRollsAndNowhereElse) {
    SceneDescription scene = bundledScene();
    scene.wind.waveAmplitude_m_s = 0.f;
    scene.wind.gustAmplitude_m_s = scene.wind.turbulenceAmplitude_m_s = 0.f;
    SceneBlades blades = buildSceneBlades(scene);
    ASSERT_EQ(blades.colliders.size(), 1u);
    const ColliderShape& roller = blades.colliders.front();
    ASSERT_GE(roller.spheres.size(), 3u) << "a capsule takes several spheres";
    const ColliderDescription& path = scene.colliders.front();
    const std::size_t n = blades.blades.size();
    std::vector<float> restHeight(n);
    for (std::size_t i = 0; i < n; ++i)
        restHeight[i] = restTipHeight(blades.blades[i], blades.rests[i]);
    constexpr int kFrames = 90;  // 3 s: the roller goes from x = -3 m to 0
    for (int f = 1; f <= kFrames; ++f) {
        const float t = static_cast<float>(f) * kFrame_s;
        std::vector<CollisionSphere> spheres;
        for (const CollisionSphere& s : roller.spheres)
            spheres.push_back({path.positionAt(t) + s.center_m, s.radius_m});
        stepFrame(blades, scene, t, spheres);
    }
    const glm::vec3 at = path.positionAt(static_cast<float>(kFrames) * kFrame_s);
    double trail = 0.0, trailRest = 0.0, aside = 0.0, asideRest = 0.0;
    int trailCount = 0, asideCount = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::vec3 root = glm::vec3(blades.blades[i].v0_height);
        const float behind = at.x - root.x, across = std::abs(root.z - at.z);
        if (behind > 0.2f && behind < 0.6f && across < 0.3f) {
            trail += tipHeight(blades.blades[i]), trailRest += restHeight[i], ++trailCount;
        } else if (behind > -0.5f && behind < 3.f && across > 1.f && across < 2.f) {
            aside += tipHeight(blades.blades[i]), asideRest += restHeight[i], ++asideCount;
        }
    }
    ASSERT_GE(trailCount, 10);
    ASSERT_GE(asideCount, 100);
    EXPECT_LT(trail / trailRest, 0.7) << trailCount << " blades in the trail";
    EXPECT_GT(aside / asideRest, 0.9) << asideCount << " blades beside the path";
}

}  // namespace
}  // namespace meadow::runtime
