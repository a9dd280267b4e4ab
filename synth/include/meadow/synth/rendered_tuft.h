#pragma once
// A synthetic tuft rendered in memory through the simulated sensor, frame for frame as
// `meadow synth` writes it (the same noise seeds, synthFrameSeed), with the truth of its first
// frame: what the accuracy tests and benches score capture against.
#include <cstdint>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "meadow/capture/depth_frame.h"
#include "meadow/synth/simulated_sensor.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::synth {

struct RenderedTuft {
    std::string preset;
    float noise = 1.f;  // as given; the sensor ran at noise x the preset's multiplier
    std::uint64_t seed = 1;
    float distance_m = 0.f;                   // the camera distance used
    std::vector<capture::DepthFrame> frames;  // each with its own sensor noise (and wind pose)
    cv::Mat1w labels;                         // truth of frame 0: blade id per pixel, 0 = none
    cv::Mat1f exact_m;                        // noise-free depth of frame 0, 0 where nothing
    SyntheticTuft tuft;                       // frame 0
};

// Edits the sensor's noise model after the preset's scale is set (a term switched off, ...).
using NoiseAdjustment = std::function<void(NoiseModel&)>;
// The sensor's noise seed of each frame of a run seeded `seed`; synthFrameSeed by default.
using FrameSeeds = std::function<std::uint64_t(std::uint64_t seed, int frame)>;

// `frameCount` frames of a preset; distance_m 0 is the preset's own. Throws SynthError for an
// unknown preset.
[[nodiscard]] RenderedTuft renderTuft(std::string_view preset, float noise, std::uint64_t seed,
                                      float distance_m, int frameCount,
                                      const NoiseAdjustment& adjust = {},
                                      const FrameSeeds& frameSeeds = {});
// The same for a tuft spec of one's own (a preset's spec, edited), under `noise`.
[[nodiscard]] RenderedTuft renderTuftSpec(const TuftSpec& spec, const NoiseModel& noise,
                                          std::uint64_t seed, int frameCount,
                                          const FrameSeeds& frameSeeds = {});

}  // namespace meadow::synth
