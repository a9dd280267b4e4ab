// 13. The motion test on the presets and on the wind preset made gentler (tables.h).
#include <glm/geometric.hpp>
#include <iostream>
#include <span>
#include <sstream>

#include "accuracy_tradeoff/tables.h"
#include "common/report.h"
#include "meadow/capture/tuft_motion.h"

namespace meadow::bench {
namespace {

constexpr int kRunFrames = 12;  // capture's default run of recurring frames

// The motion test as capture runs it: over a run of 12 frames, in the band of its first group.
capture::TuftMotion motionOf(const synth::RenderedTuft& t) {
    const int group = modeling::CaptureOptions{}.groups.fusionFrames;
    const capture::Segmentation seg = capture::Segmenter().segment(
        std::span<const capture::DepthFrame>(t.frames.data(), static_cast<std::size_t>(group)));
    return capture::tuftMotion(t.frames, seg.nearDepth_m, seg.farDepth_m);
}

// How far any blade tip moves in the image over the run, from its pose in the first frame.
float tipMotion_px(const synth::TuftSpec& spec) {
    const synth::SyntheticTuft first = synth::buildTuft(spec, 0);
    float most = 0.f;
    for (int i = 1; i < kRunFrames; ++i) {
        const synth::SyntheticTuft t = synth::buildTuft(spec, i);
        for (std::size_t b = 0; b < t.blades.size(); ++b)
            most = std::max(
                most, glm::distance(
                          spec.camera.intrinsics.project(t.blades[b].spineInCamera_m().v2),
                          spec.camera.intrinsics.project(first.blades[b].spineInCamera_m().v2)));
    }
    return most;
}

}  // namespace

void motionCalibration(const Plan& plan, const std::filesystem::path& out) {
    std::cout << "motion calibration: every preset x " << plan.motionSeeds << " seeds, wind x "
              << plan.gentlerWinds.size() << " strengths\n";
    const capture::MotionParams params;
    std::ostringstream csv, md;
    csv << "preset,swing_per_height,seed,tip_motion_px,near_changed_pct,far_changed_pct,ratio,"
           "moved\n";
    md << "| preset | wind swing per height | seed | tips move (px) | readings changed 1 / "
       << params.farLag
       << " frames apart (%) | ratio | taken for |\n|---|---|---|---|---|---|---|\n";
    const auto row = [&](const std::string& preset, const std::string& swing, int seed,
                         const synth::TuftSpec& spec, const capture::TuftMotion& m) {
        const float motion_px = tipMotion_px(spec);
        csv << preset << ',' << swing << ',' << seed << ',' << fixed(motion_px, 2) << ','
            << fixed(kPercent * m.nearChanged, 2) << ',' << fixed(kPercent * m.farChanged, 2) << ','
            << fixed(m.ratio(), 2) << ',' << (m.moved(params) ? 1 : 0) << '\n';
        md << "| " << preset << " | " << swing << " | " << seed << " | " << fixed(motion_px, 1)
           << " | " << fixed(kPercent * m.nearChanged, 2) << " / "
           << fixed(kPercent * m.farChanged, 2) << " | " << fixed(m.ratio(), 2) << " | "
           << (m.moved(params) ? "moving" : "still") << " |\n";
    };
    for (const synth::SynthPreset& preset : synth::synthPresets())
        for (int seed = 1; seed <= plan.motionSeeds; ++seed) {
            const synth::RenderedTuft t = synth::renderTuft(
                preset.name, kNominalNoise, static_cast<std::uint64_t>(seed), 0.f, kRunFrames);
            synth::TuftParams tp;
            tp.seed = static_cast<std::uint64_t>(seed);
            row(preset.name, "preset's", seed, synth::buildPresetSpec(preset, tp), motionOf(t));
        }
    const synth::SynthPreset* wind = synth::findSynthPreset("wind");
    for (const float swing : plan.gentlerWinds)
        for (int seed = 1; seed <= plan.motionSeeds; ++seed) {
            synth::TuftParams tp;
            tp.seed = static_cast<std::uint64_t>(seed);
            synth::TuftSpec spec = synth::buildPresetSpec(*wind, tp);
            spec.wind.tipDisplacementPerHeight = swing;
            synth::NoiseModel noise;
            noise.scale = kNominalNoise * wind->noiseMultiplier;
            const synth::RenderedTuft t =
                synth::renderTuftSpec(spec, noise, static_cast<std::uint64_t>(seed), kRunFrames);
            row("wind", fixed(swing, 3), seed, spec, motionOf(t));
        }
    md << "\nThe motion test (capture/tuft_motion.h) over 12 frames in the band of the first group "
          "of 3: a run is taken for moving when readings changed "
       << params.farLag << " frames apart number at least " << fixed(params.movedRatio, 1)
       << " times those changed 1 frame apart and at least "
       << fixed(kPercent * params.minMovedShare, 0)
       << " % of the readings more. Every preset holds still but wind; the wind rows scale its "
          "swing down.\n";
    writeText(out / "motion_calibration.csv", csv.str());
    writeText(out / "motion_calibration.md", md.str());
}

}  // namespace meadow::bench
