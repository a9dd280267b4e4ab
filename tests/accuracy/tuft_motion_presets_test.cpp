// The motion test (capture/tuft_motion.h) on the simulated presets, as `meadow capture` runs it
// before a run's recurring readings are used: 12 frames, in the band of the run's first fused
// group. The wind preset's tuft sways (its truth moves frame by frame); every other preset holds
// still, and only the sensor's noise changes between frames. The bench's motion_calibration
// table measures the ratios and the gentler winds.
#include <gtest/gtest.h>

#include <span>
#include <string>

#include "meadow/capture/segmenter.h"
#include "meadow/capture/tuft_motion.h"
#include "meadow/synth/rendered_tuft.h"

namespace meadow::capture {
namespace {

// The motion of 12 frames of a preset, in the band of its first fused group.
TuftMotion motionOf(const std::string& preset, std::uint64_t seed) {
    const synth::RenderedTuft t = synth::renderTuft(preset, 1.f, seed, 0.f, 12);
    const Segmentation seg = Segmenter().segment(std::span<const DepthFrame>(t.frames.data(), 3));
    return tuftMotion(t.frames, seg.nearDepth_m, seg.farDepth_m);
}

TEST(TuftMotionPresets, TheWindPresetMovesAndStillTuftsDoNot) {
    for (const std::uint64_t seed : {1u, 2u}) {
        const TuftMotion wind = motionOf("wind", seed);
        EXPECT_TRUE(wind.moved()) << "wind seed " << seed << ": " << wind.summary();
    }
    for (const std::string preset :
         {"quadratic-leaf", "shrub-leaf", "bamboo-leaf", "sharp-tip", "slim-grass", "noisy"}) {
        const TuftMotion still = motionOf(preset, 1);
        ASSERT_TRUE(still.measured) << preset;
        EXPECT_FALSE(still.moved()) << preset << ": " << still.summary();
        EXPECT_LT(still.ratio(), 1.2) << preset << ": " << still.summary();
    }
}

}  // namespace
}  // namespace meadow::capture
