// Scenes of the accuracy / trade-off bench (scene.h).
#include "accuracy_tradeoff/scene.h"

#include <algorithm>
#include <opencv2/core.hpp>
#include <span>
#include <stdexcept>

#include "common/report.h"
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
    return synth::renderTuft(presetName, noise, seed, distance_m, frameCount);
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
