#include "meadow/synth/rendered_tuft.h"

#include "meadow/synth/error.h"
#include "meadow/synth/synthesize.h"

namespace meadow::synth {

RenderedTuft renderTuftSpec(const TuftSpec& spec, const NoiseModel& noise, std::uint64_t seed,
                            int frameCount, const FrameSeeds& frameSeeds) {
    const SimulatedSensor sensor(spec.camera.intrinsics, noise);
    RenderedTuft out;
    out.seed = seed;
    out.distance_m = spec.camera.distance_m;
    for (int i = 0; i < frameCount; ++i) {
        SyntheticTuft tuft = buildTuft(spec, i);
        SimulatedFrame sim = sensor.render(
            tuft.meshes(),
            frameSeeds ? frameSeeds(seed, i) : synthFrameSeed(seed, static_cast<std::uint64_t>(i)));
        capture::DepthFrame frame;
        frame.depth_mm = sim.depth_mm;
        frame.intrinsics = spec.camera.intrinsics;
        frame.index = i;
        frame.timestamp_s = i / kSynthFrameRate_hz;
        out.frames.push_back(std::move(frame));
        if (i == 0) {
            out.labels = sim.labels;
            out.exact_m = sim.exact_m;
            out.tuft = std::move(tuft);
        }
    }
    return out;
}

RenderedTuft renderTuft(std::string_view presetName, float noise, std::uint64_t seed,
                        float distance_m, int frameCount, const NoiseAdjustment& adjust,
                        const FrameSeeds& frameSeeds) {
    const SynthPreset* preset = findSynthPreset(presetName);
    if (!preset)
        throw SynthError("unknown preset '" + std::string(presetName) +
                         "'; known presets: " + synthPresetNames());
    TuftParams params;
    params.seed = seed;
    params.distance_m = distance_m;
    TuftSpec spec = buildPresetSpec(*preset, params);
    spec.wind.frameRate_hz = static_cast<float>(kSynthFrameRate_hz);
    NoiseModel model;
    model.scale = noise * preset->noiseMultiplier;
    if (adjust) adjust(model);
    RenderedTuft out = renderTuftSpec(spec, model, seed, frameCount, frameSeeds);
    out.preset = presetName;
    out.noise = noise;
    return out;
}

}  // namespace meadow::synth
