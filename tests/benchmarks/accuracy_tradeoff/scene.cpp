// Scenes of the accuracy / trade-off bench (scene.h).
#include "accuracy_tradeoff/scene.h"

#include <algorithm>
#include <opencv2/core.hpp>
#include <span>
#include <stdexcept>

#include "accuracy_tradeoff/report.h"
#include "meadow/capture/group_segmenter.h"
#include "meadow/modeling/blade_observations.h"
#include "meadow/synth/simulated_sensor.h"
#include "meadow/synth/synthesize.h"

namespace meadow::bench {
namespace {

using capture::BladeContour;
using capture::DepthFrame;
using capture::Segmentation;
using modeling::BladeFit;
using modeling::CaptureOptions;
using synth::SyntheticTuft;

}  // namespace

Scene renderScene(const std::string& presetName, float noise, std::uint64_t seed, float distance_m,
                  int frameCount) {
    const synth::SynthPreset* preset = synth::findSynthPreset(presetName);
    if (!preset) throw std::invalid_argument("unknown preset " + presetName);
    synth::TuftParams params;
    params.seed = seed;
    params.distance_m = distance_m;
    synth::TuftSpec spec = synth::buildPresetSpec(*preset, params);
    spec.wind.frameRate_hz = static_cast<float>(synth::kSynthFrameRate_hz);
    synth::NoiseModel model;
    model.scale = noise * preset->noiseMultiplier;
    const synth::SimulatedSensor sensor(spec.camera.intrinsics, model);
    Scene scene{presetName, noise, seed, spec.camera.distance_m, {}, {}, {}};
    for (int i = 0; i < frameCount; ++i) {
        SyntheticTuft tuft = synth::buildTuft(spec, i);
        const synth::SimulatedFrame sim = sensor.render(
            tuft.meshes(), synth::synthFrameSeed(seed, static_cast<std::uint64_t>(i)));
        DepthFrame frame;
        frame.depth_mm = sim.depth_mm;
        frame.intrinsics = spec.camera.intrinsics;
        frame.index = i;
        frame.timestamp_s = i / synth::kSynthFrameRate_hz;
        scene.frames.push_back(std::move(frame));
        if (i == 0) {
            scene.labels = sim.labels;
            scene.tuft = std::move(tuft);
        }
    }
    return scene;
}

std::vector<Scene> tradeoffScenes(const Plan& plan) {
    std::vector<Scene> scenes;
    for (const std::string& preset : plan.bladeTypes)
        for (int seed = 1; seed <= plan.tradeoffSeeds; ++seed)
            scenes.push_back(renderScene(preset, kNominalNoise, static_cast<std::uint64_t>(seed),
                                         0.f, kMaxFusionFrames));
    return scenes;
}

void SegmentationTally::add(const BladeMatch& match, const capture::Segmentation& seg) {
    const auto nTrue = static_cast<double>(match.trueIds.size());
    const auto nFound = static_cast<double>(seg.blades.size());
    trueBlades += nTrue;
    foundBlades += nFound;
    recall.push_back(nTrue > 0 ? match.matched / nTrue : 1.0);
    if (nFound > 0) precision.push_back(match.matched / nFound);  // else undefined
    medianIou.push_back(median(match.trueBestIou));
    emptyFrames += seg.empty();
}

BladeMatch matchBlades(const cv::Mat1w& labels, const std::vector<BladeContour>& blades) {
    BladeMatch m;
    double maxLabel = 0;
    cv::minMaxLoc(labels, nullptr, &maxLabel);
    std::vector<cv::Mat1b> truthMasks;
    for (int id = 1; id <= static_cast<int>(maxLabel); ++id) {
        cv::Mat1b mask = labels == id;
        if (cv::countNonZero(mask) == 0) continue;
        m.trueIds.push_back(id);
        truthMasks.push_back(std::move(mask));
    }
    struct Pair {
        double iou;
        std::size_t t, f;
    };
    std::vector<Pair> pairs;
    std::vector<cv::Mat1b> found;
    for (const auto& b : blades)
        found.push_back(truthMasks.empty() ? b.mask : b.frameMask(truthMasks[0].size()));
    for (std::size_t t = 0; t < truthMasks.size(); ++t)
        for (std::size_t f = 0; f < blades.size(); ++f) {
            const double inter = cv::countNonZero(truthMasks[t] & found[f]);
            if (inter == 0) continue;
            pairs.push_back({inter / cv::countNonZero(truthMasks[t] | found[f]), t, f});
        }
    std::sort(pairs.begin(), pairs.end(),
              [](const Pair& a, const Pair& b) { return a.iou > b.iou; });
    m.trueBestIou.assign(truthMasks.size(), 0.0);
    m.foundToTrueId.assign(blades.size(), 0);
    std::vector<char> tUsed(truthMasks.size(), 0), fUsed(blades.size(), 0);
    for (const Pair& p : pairs) {
        if (tUsed[p.t] || fUsed[p.f]) continue;
        tUsed[p.t] = fUsed[p.f] = 1;
        m.trueBestIou[p.t] = p.iou;
        if (p.iou >= kMatchIou) {
            ++m.matched;
            m.foundToTrueId[p.f] = m.trueIds[p.t];
        }
    }
    return m;
}

Segmentation segmentScene(const capture::Segmenter& segmenter, const Scene& scene,
                          int fusionFrames) {
    if (fusionFrames <= 1) return segmenter.segment(scene.frames.front());
    return segmenter.segment(
        std::span<const DepthFrame>(scene.frames.data(), static_cast<std::size_t>(fusionFrames)));
}

TuftCapture captureTuft(const capture::Segmenter& segmenter, const Scene& scene,
                        const CaptureOptions& options) {
    // One group of the scene's first frames, observed and fitted as `meadow capture` does.
    capture::GroupSegmenter grouper(segmenter, options.groups);
    for (int i = 0; i < options.groups.fusionFrames; ++i)
        (void)grouper.add(scene.frames[static_cast<std::size_t>(i)]);
    std::vector<capture::GroupSegmentation> groups = grouper.finish();
    TuftCapture out;
    out.segmentation = groups.front().segmentation;
    modeling::BladeObservations seen;
    modeling::CaptureSummary summary;
    modeling::observeGroup(groups.front(), options, seen, summary);
    modeling::BladeTrackParams perGroup = options.tracks;
    perGroup.enabled = false;
    out.fits.resize(out.segmentation.blades.size());
    for (modeling::TrackFit& fitted : modeling::fitTracks(
             seen, modeling::trackObservations(seen, perGroup), options, "", summary)) {
        const int id = seen.views[fitted.track.front()].sighting.bladeId;
        for (std::size_t b = 0; b < out.segmentation.blades.size(); ++b)
            if (out.segmentation.blades[b].id == id) out.fits[b] = std::move(fitted.fit);
    }
    for (const std::string& note : summary.notes)
        out.fitFailures += note.find(" not modelled: ") != std::string::npos;
    return out;
}

}  // namespace meadow::bench
