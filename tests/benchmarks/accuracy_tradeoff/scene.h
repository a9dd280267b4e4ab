#pragma once
// Scenes of the accuracy / trade-off bench: a preset rendered in memory through the simulated
// sensor as `meadow synth` renders it, its segmentation, found blades matched to true ones by
// pixel IoU, and the capture of a tuft (segmentation + a fit of every trustworthy blade).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "accuracy_tradeoff/plan.h"
#include "meadow/capture/segmenter.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/capture_pipeline.h"
#include "meadow/synth/blade_match.h"
#include "meadow/synth/rendered_tuft.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::bench {

// A preset rendered in memory as `meadow synth` renders it, with the truth of its first frame.
using Scene = synth::RenderedTuft;

// `frameCount` frames of the preset (distance 0: the preset's own), each with its own noise.
Scene renderScene(const std::string& presetName, float noise, std::uint64_t seed, float distance_m,
                  int frameCount);
// The blade-type presets at nominal noise, kMaxFusionFrames frames each: the trade-offs' scenes.
std::vector<Scene> tradeoffScenes(const Plan& plan);

using synth::BladeMatch;
using synth::matchBlades;

// Recall, precision and median IoU frame by frame, and the blade counts, over several frames.
struct SegmentationTally {
    std::vector<double> recall, precision, medianIou;  // precision: frames that found a blade
    double trueBlades = 0.0, foundBlades = 0.0;
    int emptyFrames = 0;
    void add(const BladeMatch& match, const capture::Segmentation& seg);
};

// The scene's first frame, or its first `fusionFrames` fused.
capture::Segmentation segmentScene(const capture::Segmenter& segmenter, const Scene& scene,
                                   int fusionFrames);

// modeling::captureArchetypes for one fused group (its steps, one by one), keeping what
// the library drops (the blade masks and camera-space spines) to compare with the truth.
struct TuftCapture {
    capture::Segmentation segmentation;
    std::vector<std::optional<modeling::BladeFit>> fits;  // per found blade; empty when skipped
    int fitFailures = 0;
};
TuftCapture captureTuft(const capture::Segmenter& segmenter, const Scene& scene,
                        const modeling::CaptureOptions& options);

}  // namespace meadow::bench
