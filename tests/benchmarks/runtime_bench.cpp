// Per-blade physics and culling (Jahrmann & Wimmer 2017, Sec. 5): GPU passes (whatever driver
// the EGL context gets: Mesa llvmpipe without a GPU) and their CPU references, 10k to 1M blades.
// Counters: time_per_blade (seconds per blade per step, SI-prefixed), visible (blades that survived
// culling). Run: build/<dir>/tests/meadow_runtime_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <random>
#include <vector>

#include "culling_pass.h"
#include "culling_reference.h"
#include "meadow/runtime/gl_context.h"
#include "physics_pass.h"
#include "physics_reference.h"
#include "runtime/physics_test_blades.h"

namespace meadow::runtime {
namespace {

constexpr float kDt_s = 1.f / 60.f;
constexpr std::uint32_t kPatchBlades = 256;

GlContext& context() {
    static GlContext c;  // one context for the whole program, created on first GPU benchmark
    return c;
}

template <class T>
gl::Buffer upload(const std::vector<T>& data) {
    gl::Buffer b = gl::Buffer::create();
    glNamedBufferStorage(b.id(), data.size() * sizeof(T), data.data(), GL_DYNAMIC_STORAGE_BIT);
    return b;
}

// Eight spheres rolling through the meadow (collisions on), or none.
std::vector<CollisionSphere> spheres(bool on, float extent_m, std::uint32_t frame) {
    std::vector<CollisionSphere> s;
    if (!on) return s;
    const float t = static_cast<float>(frame) * kDt_s;
    for (int k = 0; k < 8; ++k)
        s.push_back({{0.4f * extent_m * std::cos(0.3f * t + k), 0.2f,
                      0.4f * extent_m * std::sin(0.5f * t + k)},
                     0.5f});
    return s;
}

// Side (m) of a square meadow of `blades` at 400 blades / m^2.
float extentFor(std::uint32_t blades) { return std::sqrt(static_cast<float>(blades) / 400.f); }

void setCounters(benchmark::State& state, std::uint32_t blades) {
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * blades);
    // Seconds per blade per step (printed with an SI prefix: "250n" = 250 ns), over CPU time for
    // the CPU references and wall time for the GPU passes (UseRealTime).
    state.counters["time_per_blade"] =
        benchmark::Counter(static_cast<double>(state.iterations()) * blades,
                           benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_PhysicsCpuReference(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    const bool collisions = state.range(1) != 0;
    const float extent = extentFor(n);
    testing::TestMeadow m = testing::makeTestMeadow(n, 1, extent);
    const PhysicsSettings settings = testing::stormSettings();
    std::uint32_t frame = 0;
    for (auto _ : state) {
        const auto colliders = packColliders(spheres(collisions, extent, frame));
        physicsStepReference(m.blades, m.rests, colliders,
                             packPhysicsParams(settings, kDt_s, frame * kDt_s, n,
                                               static_cast<std::uint32_t>(colliders.size())));
        ++frame;
        benchmark::DoNotOptimize(m.blades.data());
    }
    setCounters(state, n);
}

void BM_PhysicsGpu(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    const bool collisions = state.range(1) != 0;
    const float extent = extentFor(n);
    GlContext& ctx = context();
    PhysicsPass pass(ctx);
    const testing::TestMeadow m = testing::makeTestMeadow(n, 1, extent);
    const gl::Buffer blades = upload(m.blades), rests = upload(m.rests);
    const PhysicsSettings settings = testing::stormSettings();
    // llvmpipe compiles the shader on its first dispatch: keep that out of the timing.
    pass.dispatch(blades, rests, n, spheres(collisions, extent, 0), settings, kDt_s, 0.f);
    ctx.finish();
    std::uint32_t frame = 1;
    for (auto _ : state) {
        pass.dispatch(blades, rests, n, spheres(collisions, extent, frame), settings, kDt_s,
                      frame * kDt_s);
        ctx.finish();  // time the work, not the submission
        ++frame;
    }
    setCounters(state, n);
}

// A square meadow of n blades in patches of 256 (16 x 16 blade cells, locality-sorted), seen from
// its edge at 1.7 m, with an opaque wall over the right third of a 320 x 180 depth image.
struct BenchScene {
    std::vector<gpu::BladeGpu> blades;
    std::vector<gpu::PatchGpu> patches;
    CullCamera camera;
    std::uint32_t depthWidth = 320, depthHeight = 180;
    std::vector<float> depth;
};

BenchScene makeBenchScene(std::uint32_t n) {
    BenchScene s;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.f, 1.f);
    const auto patchesPerSide =
        static_cast<std::uint32_t>(std::ceil(std::sqrt(n / double(kPatchBlades))));
    const float patch_m = 0.8f;  // 256 blades on 0.64 m^2: 400 blades / m^2
    const float half = 0.5f * patch_m * patchesPerSide;
    for (std::uint32_t pz = 0; pz < patchesPerSide && s.blades.size() < n; ++pz)
        for (std::uint32_t px = 0; px < patchesPerSide && s.blades.size() < n; ++px) {
            const glm::vec3 corner{px * patch_m - half, 0.f, pz * patch_m - half};
            const auto first = static_cast<std::uint32_t>(s.blades.size());
            const std::uint32_t count = std::min<std::uint32_t>(kPatchBlades, n - first);
            for (std::uint32_t i = 0; i < count; ++i) {
                const glm::vec3 v0 =
                    corner + glm::vec3(patch_m * ((i % 16) + unit(rng)) / 16.f, 0.f,
                                       patch_m * ((i / 16) + unit(rng)) / 16.f);
                const float h = 0.3f + 0.4f * unit(rng);
                const glm::vec3 tip = v0 + glm::vec3(0.f, h, 0.f);
                s.blades.push_back({glm::vec4(v0, h), glm::vec4(tip, 0.01f), glm::vec4(tip, 10.f),
                                    glm::vec4(0.f, 1.f, 0.f, 6.2831853f * unit(rng))});
            }
            s.patches.push_back(
                {glm::vec4(corner - glm::vec3(0.7f, 0.f, 0.7f), 0.f),
                 glm::vec4(corner + glm::vec3(patch_m + 0.7f, 0.7f, patch_m + 0.7f), 0.f),
                 glm::uvec4(first, count, 0, 0)});
        }
    const glm::vec3 eye{0.f, 1.7f, half + 2.f};
    s.camera.position_m = eye;
    s.camera.near_m = 0.1f;
    s.camera.far_m = 200.f;
    s.camera.clipFromWorld = glm::perspective(glm::radians(60.f), 16.f / 9.f, 0.1f, 200.f) *
                             glm::lookAt(eye, glm::vec3(0.f, 0.f, 0.f), glm::vec3(0.f, 1.f, 0.f));
    s.depth.assign(std::size_t{s.depthWidth} * s.depthHeight, 1.f);
    const float wall = 0.985f;  // window depth of a wall ~6.7 m away (near 0.1 m, far 200 m)
    for (std::uint32_t y = 0; y < s.depthHeight; ++y)
        for (std::uint32_t x = 2 * s.depthWidth / 3; x < s.depthWidth; ++x)
            s.depth[y * s.depthWidth + x] = wall;
    return s;
}

CullSettings cullSettings(bool on) {
    CullSettings c;
    c.maxDistance_m = 40.f;
    c.distanceLevels = 8;
    c.orientation = c.frustum = c.distance = c.occlusion = on;
    return c;
}

void BM_CullCpuReference(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    const bool on = state.range(1) != 0;
    const BenchScene s = makeBenchScene(n);
    const DepthImageView depth{s.depthWidth, s.depthHeight, s.depth};
    const auto params = packCullParams(
        cullSettings(on), s.camera.clipFromWorld, s.camera.position_m, s.camera.near_m,
        s.camera.far_m, static_cast<std::uint32_t>(s.patches.size()), s.depthWidth, s.depthHeight);
    std::size_t visible = 0;
    for (auto _ : state) {
        const CullResult r = cullReference(s.blades, s.patches, params, &depth);
        visible = r.visible.size();
        benchmark::DoNotOptimize(visible);
    }
    setCounters(state, n);
    state.counters["visible"] = static_cast<double>(visible);
}

void BM_CullGpu(benchmark::State& state) {
    const auto n = static_cast<std::uint32_t>(state.range(0));
    const bool on = state.range(1) != 0;
    GlContext& ctx = context();
    const BenchScene s = makeBenchScene(n);
    CullingPass pass(ctx, n);
    const gl::Buffer blades = upload(s.blades), patches = upload(s.patches);
    gl::Texture depthTexture = gl::Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(depthTexture.id(), 1, GL_DEPTH_COMPONENT32F, s.depthWidth, s.depthHeight);
    glTextureSubImage2D(depthTexture.id(), 0, 0, 0, s.depthWidth, s.depthHeight, GL_DEPTH_COMPONENT,
                        GL_FLOAT, s.depth.data());
    const CullDepth depth{depthTexture, s.depthWidth, s.depthHeight};
    // llvmpipe compiles the shader on its first dispatch: keep that out of the timing.
    pass.dispatch(blades, n, patches, static_cast<std::uint32_t>(s.patches.size()), s.camera,
                  cullSettings(on), &depth);
    ctx.finish();
    for (auto _ : state) {
        pass.dispatch(blades, n, patches, static_cast<std::uint32_t>(s.patches.size()), s.camera,
                      cullSettings(on), &depth);
        ctx.finish();
    }
    setCounters(state, n);
    state.counters["visible"] = static_cast<double>(pass.readDrawCommand().vertexCount);
}

void bladeCounts(benchmark::internal::Benchmark* b) {
    for (std::int64_t n : {10'000, 100'000, 1'000'000})
        for (std::int64_t flag : {0, 1}) b->Args({n, flag});
    b->ArgNames({"blades", "on"});
    b->Unit(benchmark::kMillisecond);
}

// "on" is collisions (8 spheres) for physics and all four culling tests for culling.
BENCHMARK(BM_PhysicsCpuReference)->Apply(bladeCounts);
BENCHMARK(BM_PhysicsGpu)->Apply(bladeCounts)->UseRealTime();
BENCHMARK(BM_CullCpuReference)->Apply(bladeCounts);
BENCHMARK(BM_CullGpu)->Apply(bladeCounts)->UseRealTime();

}  // namespace
}  // namespace meadow::runtime

BENCHMARK_MAIN();
