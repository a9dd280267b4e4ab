// The motion test (capture/tuft_motion.h) on the simulated presets, as `meadow capture` runs it
// before a run's recurring readings are used: 12 frames, in the band of the run's first fused
// group. The wind preset's tuft sways (its truth moves frame by frame); every other preset holds
// still, and only the sensor's noise changes between frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <iostream>
#include <span>

#include "meadow/capture/segmenter.h"
#include "meadow/capture/tuft_motion.h"
#include "meadow/synth/simulated_sensor.h"
#include "meadow/synth/synthesize.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::modeling {
namespace {
using namespace synth;

// The motion of 12 frames of `spec`'s tuft, in the band of its first fused group.
capture::TuftMotion motionOf(const TuftSpec& spec, std::uint64_t seed, float noiseScale) {
    synth::NoiseModel noise;
    noise.scale = noiseScale;
    const synth::SimulatedSensor sensor(spec.camera.intrinsics, noise);
    std::vector<capture::DepthFrame> frames(12);
    for (int i = 0; i < 12; ++i) {
        auto& f = frames[static_cast<std::size_t>(i)];
        f.depth_mm = sensor
                         .render(buildTuft(spec, i).meshes(),
                                 synthFrameSeed(seed, static_cast<std::uint64_t>(i)))
                         .depth_mm;
        f.intrinsics = spec.camera.intrinsics;
        f.index = i;
    }
    const capture::Segmentation seg =
        capture::Segmenter().segment(std::span<const capture::DepthFrame>(frames.data(), 3));
    return capture::tuftMotion(frames, seg.nearDepth_m, seg.farDepth_m);
}

capture::TuftMotion motionOf(const std::string& presetName, std::uint64_t seed) {
    const SynthPreset* preset = findSynthPreset(presetName);
    if (!preset) throw std::invalid_argument("no preset " + presetName);
    TuftParams params;
    params.seed = seed;
    const capture::TuftMotion m =
        motionOf(buildPresetSpec(*preset, params), seed, preset->noiseMultiplier);
    std::cout << "  " << presetName << " seed " << seed << ": " << m.summary() << '\n';
    return m;
}

// Measured (seeds 1-3): wind 2.1-2.8x (0.6-1.0 m); the still presets 0.95-1.05x, noisy (3x noise)
// and slim grass included, whose readings change most from frame to frame (10-17 % and 3-4 %).
TEST(TuftMotionPresets, TheWindPresetMovesAndStillTuftsDoNot) {
    for (const std::uint64_t seed : {1u, 2u}) {
        const capture::TuftMotion wind = motionOf("wind", seed);
        EXPECT_TRUE(wind.moved()) << "wind seed " << seed << ": " << wind.summary();
    }
    for (const std::string preset :
         {"quadratic-leaf", "shrub-leaf", "bamboo-leaf", "sharp-tip", "slim-grass", "noisy"}) {
        const capture::TuftMotion still = motionOf(preset, 1);
        ASSERT_TRUE(still.measured) << preset;
        EXPECT_FALSE(still.moved()) << preset << ": " << still.summary();
        EXPECT_LT(still.ratio(), 1.2) << preset;
    }
}

// The wind preset made gentler: how far its tips move over the 12 frames against what the motion
// test measures. Printed for the README ("Why the 1 % as well"), not asserted.
TEST(TuftMotionPresets, PrintsGentlerWind) {
    if (!std::getenv("MEADOW_MOTION_TABLE")) GTEST_SKIP() << "set MEADOW_MOTION_TABLE=1";
    const SynthPreset* preset = findSynthPreset("wind");
    ASSERT_NE(preset, nullptr);
    std::cout << "| swing per height | seed | tips move (px) | motion |\n|---|---|---|---|\n";
    for (const float swing : {0.f, 0.005f, 0.01f, 0.02f, 0.05f, 0.1f, 0.3f})
        for (const std::uint64_t seed : {1u, 2u}) {
            TuftParams params;
            params.seed = seed;
            TuftSpec spec = buildPresetSpec(*preset, params);
            spec.wind.tipDisplacementPerHeight = swing;
            const SyntheticTuft first = buildTuft(spec, 0);
            float tipMotion_px = 0.f;
            for (int i = 1; i < 12; ++i) {
                const SyntheticTuft t = buildTuft(spec, i);
                for (std::size_t b = 0; b < t.blades.size(); ++b)
                    tipMotion_px = std::max(
                        tipMotion_px,
                        glm::distance(
                            spec.camera.intrinsics.project(t.blades[b].spineInCamera_m().v2),
                            spec.camera.intrinsics.project(first.blades[b].spineInCamera_m().v2)));
            }
            std::cout << "| " << swing << " | " << seed << " | " << tipMotion_px << " | "
                      << motionOf(spec, seed, preset->noiseMultiplier).summary() << " |\n";
        }
}

}  // namespace
}  // namespace meadow::modeling
