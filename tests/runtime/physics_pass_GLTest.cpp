// The GPU physics pass (shaders/physics.comp) against its CPU reference, and the brief's
// invariants on the GPU over the same 10,000-frame storm the CPU reference runs.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <glm/geometric.hpp>
#include <iostream>
#include <vector>

#include "meadow/modeling/quadratic_bezier.h"
#include "physics_pass.h"
#include "physics_test_blades.h"

namespace meadow::runtime {
namespace {

constexpr float kDt_s = 1.f / 60.f;

template <class T>
gl::Buffer upload(const std::vector<T>& data) {
    gl::Buffer b = gl::Buffer::create();
    glNamedBufferStorage(b.id(), data.size() * sizeof(T), data.data(), GL_DYNAMIC_STORAGE_BIT);
    return b;
}

template <class T>
std::vector<T> download(const gl::Buffer& b, std::size_t count) {
    std::vector<T> out(count);
    glGetNamedBufferSubData(b.id(), 0, count * sizeof(T), out.data());
    return out;
}

struct GpuMeadow {
    gl::Buffer blades, rests;
    std::uint32_t count;
    explicit GpuMeadow(const testing::TestMeadow& m)
        : blades(upload(m.blades)),
          rests(upload(m.rests)),
          count(static_cast<std::uint32_t>(m.blades.size())) {}
};

void cpuStep(testing::TestMeadow& m, const PhysicsSettings& s, std::uint32_t f,
             const std::vector<CollisionSphere>& spheres) {
    const auto colliders = packColliders(spheres);
    physicsStepReference(m.blades, m.rests, colliders,
                         packPhysicsParams(s, kDt_s, static_cast<float>(f) * kDt_s,
                                           static_cast<std::uint32_t>(m.blades.size()),
                                           static_cast<std::uint32_t>(colliders.size())));
}

// After K frames the GPU and the CPU differ by float rounding only (FMA contraction, the
// driver's sin/log/sqrt): both run the same text. The dynamics are contracting (recovery pulls
// toward the rest pose, validation projects), so differences do not grow; 2e-4 h over 120 storm
// frames leaves room for the driver's transcendentals (GLSL allows 2^-11 relative error for sin).
TEST(PhysicsPassGLTest, GpuMatchesCpuReferenceAfter120StormFramesWithCollisions) {
    GlContext context;
    PhysicsPass pass(context);
    testing::TestMeadow cpu = testing::makeTestMeadow(500, 21);
    GpuMeadow gpu(cpu);
    const PhysicsSettings storm = testing::stormSettings();
    for (std::uint32_t f = 0; f < 120; ++f) {
        const auto spheres = testing::sweepingSpheres(f);
        pass.dispatch(gpu.blades, gpu.rests, gpu.count, spheres, storm, kDt_s, f * kDt_s);
        cpuStep(cpu, storm, f, spheres);
    }
    const auto blades = download<gpu::BladeGpu>(gpu.blades, gpu.count);
    const auto rests = download<gpu::BladeRestGpu>(gpu.rests, gpu.count);
    float worst = 0.f, worstEta = 0.f;
    int touched = 0;
    for (std::uint32_t i = 0; i < gpu.count; ++i) {
        const float h = cpu.blades[i].v0_height.w;
        const float d2 =
            glm::distance(glm::vec3(blades[i].v2_stiffness), glm::vec3(cpu.blades[i].v2_stiffness));
        const float d1 =
            glm::distance(glm::vec3(blades[i].v1_width), glm::vec3(cpu.blades[i].v1_width));
        worst = std::max(worst, std::max(d1, d2) / h);
        worstEta = std::max(worstEta, std::abs(rests[i].restV2_eta.w - cpu.rests[i].restV2_eta.w));
        if (cpu.rests[i].restV2_eta.w > 0.f) ++touched;
        EXPECT_LT(std::max(d1, d2), 2e-4f * h) << "blade " << i << " h " << h;
    }
    EXPECT_LT(worstEta, 1e-3f);
    EXPECT_GT(touched, 0) << "no blade was hit: the comparison does not cover collisions";
    std::cout << "GPU vs CPU after 120 frames: worst control-point difference " << worst
              << " h, worst eta difference " << worstEta << ", " << touched << " blades hit\n";
}

// The brief's invariants on the GPU, for as long as the CPU reference runs them: 256 blades,
// 10,000 frames of the storm (167 s at 60 Hz) with three sweeping spheres, then 1200 calm frames
// beside a twin that only ever felt gravity. Read back every 500 frames only: a read-back stalls
// the pipeline, and the state in between is checked by the CPU reference frame by frame.
TEST(PhysicsPassGLTest,
     TenThousandStormFramesOnTheGpuKeepBladesFiniteAboveGroundAtLengthAndTheyRecover) {
    const auto started = std::chrono::steady_clock::now();
    GlContext context;
    PhysicsPass pass(context);
    const testing::TestMeadow start = testing::makeTestMeadow(256, 22);
    GpuMeadow storm(start), calm(start);
    float worstLength = 0.f, worstBelow = 0.f;
    std::uint32_t checkpoints = 0, hitAtCheckpoints = 0;
    constexpr std::uint32_t kStormFrames = 10000, kCalmFrames = 1200, kCheckEvery = 500;
    auto check = [&](std::uint32_t f) {
        ++checkpoints;
        const auto blades = download<gpu::BladeGpu>(storm.blades, storm.count);
        const auto rests = download<gpu::BladeRestGpu>(storm.rests, storm.count);
        for (std::uint32_t i = 0; i < storm.count; ++i) {
            const gpu::BladeGpu& b = blades[i];
            for (int k = 0; k < 4; ++k)
                ASSERT_TRUE(std::isfinite(b.v1_width[k]) && std::isfinite(b.v2_stiffness[k]) &&
                            std::isfinite(rests[i].restV2_eta[k]))
                    << "blade " << i << " frame " << f;
            hitAtCheckpoints += rests[i].restV2_eta.w > 0.f;
            const float h = b.v0_height.w;
            const glm::vec3 v0 = glm::vec3(b.v0_height);
            worstBelow =
                std::max(worstBelow,
                         -glm::dot(glm::vec3(b.v2_stiffness) - v0, glm::vec3(b.up_direction)) / h);
            const float L =
                modeling::QuadraticBezier{v0, glm::vec3(b.v1_width), glm::vec3(b.v2_stiffness)}
                    .length();
            worstLength = std::max(worstLength, std::abs(L - h) / h);
        }
    };
    for (std::uint32_t f = 0; f < kStormFrames + kCalmFrames; ++f) {
        const bool stormy = f < kStormFrames;
        pass.dispatch(storm.blades, storm.rests, storm.count,
                      stormy ? testing::sweepingSpheres(f) : std::vector<CollisionSphere>{},
                      stormy ? testing::stormSettings() : testing::calmSettings(), kDt_s,
                      f * kDt_s);
        pass.dispatch(calm.blades, calm.rests, calm.count, {}, testing::calmSettings(), kDt_s,
                      f * kDt_s);
        if (stormy && (f % kCheckEvery == kCheckEvery - 1)) check(f);
        if (HasFatalFailure()) return;
    }
    check(kStormFrames + kCalmFrames - 1);  // after the calm: still finite, at length
    EXPECT_EQ(checkpoints, kStormFrames / kCheckEvery + 1);
    EXPECT_GT(hitAtCheckpoints, 0u) << "the spheres never touched the meadow";
    EXPECT_LE(worstBelow, 1e-5f);
    EXPECT_LT(worstLength, 0.01f);
    const auto a = download<gpu::BladeGpu>(storm.blades, storm.count);
    const auto b = download<gpu::BladeGpu>(calm.blades, calm.count);
    const auto rests = download<gpu::BladeRestGpu>(storm.rests, storm.count);
    float worstRecovery = 0.f;
    for (std::uint32_t i = 0; i < storm.count; ++i) {
        EXPECT_EQ(rests[i].restV2_eta.w, 0.f) << "blade " << i << ": eta did not decay to 0";
        worstRecovery = std::max(worstRecovery, glm::distance(glm::vec3(a[i].v2_stiffness),
                                                              glm::vec3(b[i].v2_stiffness)) /
                                                    a[i].v0_height.w);
    }
    EXPECT_LT(worstRecovery, 1e-3f);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    std::cout << "GPU storm, " << kStormFrames << " frames: worst length error "
              << worstLength * 100.f << " %, below ground " << worstBelow << " h, recovery "
              << worstRecovery << " h, " << hitAtCheckpoints << " blade hits at checkpoints; "
              << seconds << " s wall (reported, not asserted)\n";
}

TEST(PhysicsPassGLTest, BladeUnderNoForceKeepsItsRestShapeOnTheGpu) {
    GlContext context;
    PhysicsPass pass(context);
    const testing::TestMeadow start = testing::makeTestMeadow(128, 23);
    GpuMeadow m(start);
    PhysicsSettings none = testing::calmSettings();
    none.gravity_mps2 = 0.f;
    none.gravityCenter_mps2 = 0.f;
    for (std::uint32_t f = 0; f < 300; ++f)
        pass.dispatch(m.blades, m.rests, m.count, {}, none, kDt_s, f * kDt_s);
    const auto blades = download<gpu::BladeGpu>(m.blades, m.count);
    for (std::uint32_t i = 0; i < m.count; ++i) {
        const float h = start.blades[i].v0_height.w;
        EXPECT_LT(glm::distance(glm::vec3(blades[i].v2_stiffness),
                                glm::vec3(start.blades[i].v2_stiffness)),
                  1e-5f * h)
            << i;
        EXPECT_LT(glm::distance(glm::vec3(blades[i].v1_width), glm::vec3(start.blades[i].v1_width)),
                  1e-5f * h)
            << i;
    }
}

}  // namespace
}  // namespace meadow::runtime

namespace meadow::runtime {
namespace {

// GL guarantees 65535 work groups a dimension, 4,194,240 blades of 64 in one row; the pass
// spreads more over a second dimension (gl::dispatchGroups), so the blade past that count moves
// as the first one does. The blades are copies of one blade, so both must end where it ends.
TEST(PhysicsPassGLTest, MoreBladesThanOneDispatchRowReachesTheLastBlade) {
    constexpr std::uint32_t kCount = 65535u * BLADE_WORKGROUP_SIZE + 3000u;
    GlContext context;
    PhysicsPass pass(context);
    const testing::TestMeadow one = testing::makeTestMeadow(1, 4);
    const std::vector<gpu::BladeGpu> blades(kCount, one.blades.front());
    const std::vector<gpu::BladeRestGpu> rests(kCount, one.rests.front());
    gl::Buffer b = upload(blades), r = upload(rests);
    const PhysicsSettings storm = testing::stormSettings();
    pass.dispatch(b, r, kCount, {}, storm, kDt_s, 0.f);
    gpu::BladeGpu first{}, last{};
    glGetNamedBufferSubData(b.id(), 0, sizeof first, &first);
    glGetNamedBufferSubData(b.id(), (kCount - 1) * sizeof last, sizeof last, &last);
    EXPECT_NE(glm::vec3(first.v2_stiffness), glm::vec3(one.blades.front().v2_stiffness))
        << "the storm moves the tip";
    EXPECT_EQ(glm::vec3(last.v2_stiffness), glm::vec3(first.v2_stiffness))
        << "blade " << kCount - 1 << " was not simulated";
}

}  // namespace
}  // namespace meadow::runtime
