// Whole frames of the renderer (Jahrmann & Wimmer 2017, the shape of Tables 1 and 3): a square
// meadow of n blades (400 / m^2) seen across from its edge, 640 x 360 with 4x MSAA, physics with
// wind and gravity, in three configurations:
//   all        physics + collisions (four spheres rolling through) + every culling test
//   no_coll    the same without colliders
//   no_cull    physics + collisions, no culling pass (every blade drawn)
// Frames are rendered pipelined (Renderer::renderFrames, no images), in batches of up to
// kFramesPerBatch, one benchmark iteration per frame: wall time per frame (each batch drains its
// pipeline) and, from the renderer's GPU timer queries, the milliseconds of each stage.
// Whatever driver EGL gets: Mesa llvmpipe without a GPU.
// Run: build/<dir>/tests/meadow_frame_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

constexpr float kDensity_per_m2 = 400.f;
// Frames per renderFrames call: long enough that filling and draining the three frames in
// flight is a small part of it, short enough for the 1 s minimum time at 100 k on llvmpipe.
constexpr std::int64_t kFramesPerBatch = 8;

enum Mode : int { kAll = 0, kNoCollisions = 1, kNoCulling = 2 };

GlContext& context() {
    static GlContext c;  // one context for the whole program
    return c;
}

SceneDescription benchScene(std::int64_t blades, bool collisions) {
    const float side = std::sqrt(static_cast<float>(blades) / kDensity_per_m2);
    const float half = 0.5f * side;
    const auto dir = test::freshTestDirectory("frame_bench_" + std::to_string(blades));
    test::writeQuad(dir / "ground.gltf", -half, half, -half, half);
    nlohmann::json colliders = nlohmann::json::array();
    if (collisions)
        for (int k = 0; k < 4; ++k)
            colliders.push_back({{"center_m", {-half + 0.25 * side * k, 0.3, 0.3 * half}},
                                 {"radius_m", 0.3},
                                 {"velocity_m_s", {0.5, 0, -0.3}}});
    const nlohmann::json extra = {
        {"blades", {{"density_per_m2", kDensity_per_m2}, {"seed", 7}}},
        {"camera",
         {{"path",
           {{{"time_s", 0}, {"position_m", {0, 1.6, half + 1.5}}, {"target_m", {0, 0.2, 0}}}}},
          {"vertical_fov_deg", 50},
          {"near_m", 0.05},
          {"far_m", 200}}},
        {"colliders", colliders},
        {"physics", {{"enabled", true}}},
        {"render", {{"size_px", {640, 360}}, {"msaa_samples", 4}, {"patch_size", 256}}}};
    return loadSceneDescription(test::writeScene(dir, test::minimalScene("ground.gltf", extra)));
}

void BM_Frame(benchmark::State& state) {
    const std::int64_t n = state.range(0);
    const auto mode = static_cast<Mode>(state.range(1));
    GlContext& ctx = context();
    const SceneDescription scene = benchScene(n, mode != kNoCollisions);
    Renderer renderer(ctx, scene);
    installPhysicsPass(renderer, ctx);
    if (mode != kNoCulling) installCullingPass(renderer, ctx);
    int frame = 0;
    // llvmpipe compiles the shaders on the first frames: keep that out of the timing.
    for (; frame < 2; ++frame) renderer.renderFrame(frame);
    double prepass = 0, physics = 0, culling = 0, draw = 0, resolve = 0, frameMs = 0, drawn = 0;
    const std::int64_t batch = std::min(kFramesPerBatch, state.max_iterations);
    while (state.KeepRunningBatch(batch)) {
        renderer.renderFrames(frame, static_cast<int>(batch), /*wantImages=*/false,
                              [&](RenderedFrame&& f) {
                                  const FrameStats& s = f.stats;
                                  prepass += s.gpuPrepass_ms;
                                  physics += s.gpuPhysics_ms;
                                  culling += s.gpuCulling_ms;
                                  draw += s.gpuDraw_ms;
                                  resolve += s.gpuResolve_ms;
                                  frameMs += s.frame_ms;
                                  drawn += static_cast<double>(s.bladesDrawn);
                              });
        frame += static_cast<int>(batch);
    }
    const double k = 1.0 / static_cast<double>(state.iterations());
    const double blades = static_cast<double>(renderer.bladeCount());
    state.counters["blades"] = blades;
    state.counters["drawn"] = drawn * k;
    state.counters["frame_ms"] = frameMs * k;
    state.counters["prepass_ms"] = prepass * k;
    state.counters["physics_ms"] = physics * k;
    state.counters["cull_ms"] = culling * k;
    state.counters["draw_ms"] = draw * k;
    state.counters["resolve_ms"] = resolve * k;
    state.counters["phys_ns_blade"] = physics * k * 1e6 / blades;
    state.SetLabel(mode == kAll ? "all" : mode == kNoCollisions ? "no_coll" : "no_cull");
}

// 300k blades and more take seconds per frame on llvmpipe (draw ~ linear in blades drawn):
// left out here; add {300000, ...} rows on a GPU.
BENCHMARK(BM_Frame)
    ->ArgsProduct({{10000, 30000, 100000}, {kAll, kNoCollisions, kNoCulling}})
    ->ArgNames({"blades", "mode"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(1.0);
// 1 M blades, the paper's scale: on llvmpipe a frame takes seconds, so two timed frames each.
// Run alone with --benchmark_filter=blades:1000000.
BENCHMARK(BM_Frame)
    ->ArgsProduct({{1000000}, {kAll, kNoCollisions, kNoCulling}})
    ->ArgNames({"blades", "mode"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);

}  // namespace
}  // namespace meadow::runtime

BENCHMARK_MAIN();
