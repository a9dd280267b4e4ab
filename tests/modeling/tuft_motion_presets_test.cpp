// The motion test (capture/tuft_motion.h) on the simulated presets, as `meadow capture` runs it
// before a run's recurring readings are used: 12 frames, in the band of the run's first fused
// group. The wind preset's tuft sways (its truth moves frame by frame); every other preset holds
// still, and only the sensor's noise changes between frames.
#include <gtest/gtest.h>

#include <iostream>
#include <span>

#include "meadow/capture/segmenter.h"
#include "meadow/capture/simulated_sensor.h"
#include "meadow/capture/tuft_motion.h"
#include "meadow/modeling/synthesize.h"
#include "meadow/modeling/synthetic_tuft.h"

namespace meadow::modeling {
namespace {

capture::TuftMotion motionOf(const std::string& presetName, std::uint64_t seed) {
    const SynthPreset* preset = findSynthPreset(presetName);
    if (!preset) throw std::invalid_argument("no preset " + presetName);
    TuftParams params;
    params.seed = seed;
    const TuftSpec spec = buildPresetSpec(*preset, params);
    capture::NoiseModel noise;
    noise.scale = preset->noiseMultiplier;
    const capture::SimulatedSensor sensor(spec.camera.intrinsics, noise);
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
    const capture::TuftMotion m = capture::tuftMotion(frames, seg.nearDepth_m, seg.farDepth_m);
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

}  // namespace
}  // namespace meadow::modeling
