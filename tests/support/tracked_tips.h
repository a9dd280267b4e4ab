#pragma once
// Test and bench support, header-only: a still tuft of 12 frames seen as `meadow capture` sees it
// (capture::GroupSegmenter, modeling::observeGroup, trackBlades), each view tied to the true
// blade under it, and how far the fitted tips land from the true ones, per view and per track.
// blade_tracks_accuracy_test.cpp asserts on it; the accuracy bench's tracks tables print it.
#include <cmath>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "meadow/capture/group_segmenter.h"
#include "meadow/capture/segmenter.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/blade_observations.h"
#include "meadow/modeling/blade_tracks.h"
#include "meadow/synth/blade_match.h"
#include "meadow/synth/rendered_tuft.h"

namespace meadow::test {

inline constexpr int kTrackedGroups = 4;
inline constexpr int kTrackedFusedFrames = 3;  // capture's default groups
inline constexpr int kTrackedFrames = kTrackedGroups * kTrackedFusedFrames;

// A rendered tuft's blades as capture sees them, and the true blade each view is (0: none).
struct TrackedTuft {
    synth::RenderedTuft tuft;
    modeling::BladeObservations seen;
    std::vector<int> truth;  // parallel to seen.views

    // The true blade of a track when all its views are of that one blade, else 0.
    [[nodiscard]] int trueBladeOfTrack(const std::vector<std::size_t>& track) const {
        for (const std::size_t i : track)
            if (truth[i] == 0 || truth[i] != truth[track.front()]) return 0;
        return truth[track.front()];
    }
};

// 12 frames of a still preset at nominal noise, segmented in groups of `fused` frames (fused as
// `segmenter` says); with `recurring`, the tip trails also see the readings recurring over all 12
// frames, as capture's default does. Runs are not tested for motion: the tuft holds still.
inline TrackedTuft observeTuft(const std::string& preset, float distance_m, bool recurring,
                               std::uint64_t seed, const capture::SegmenterParams& segmenter = {},
                               int fused = kTrackedFusedFrames,
                               const modeling::BladeFitParams& fit = {}) {
    TrackedTuft out{synth::renderTuft(preset, 1.f, seed, distance_m, kTrackedFrames), {}, {}};
    modeling::CaptureOptions options;
    options.segmenter = segmenter;
    options.fit = fit;
    options.groups.fusionFrames = fused;
    options.groups.recurringFrames = recurring ? kTrackedFrames : 0;
    options.groups.checkMotion = false;
    const capture::Segmenter seg(segmenter);
    capture::GroupSegmenter groups(seg, options.groups);
    std::vector<capture::GroupSegmentation> segmented;
    for (const capture::DepthFrame& frame : out.tuft.frames)
        for (auto& g : groups.add(frame)) segmented.push_back(std::move(g));
    for (auto& g : groups.finish()) segmented.push_back(std::move(g));
    modeling::CaptureSummary summary;
    for (const capture::GroupSegmentation& g : segmented) {
        const std::size_t before = out.seen.views.size();
        modeling::observeGroup(g, options, out.seen, summary);
        for (std::size_t v = before; v < out.seen.views.size(); ++v)
            for (const capture::BladeContour& blade : g.segmentation.blades)
                if (blade.id == out.seen.views[v].sighting.bladeId)
                    out.truth.push_back(synth::majorityTrueBlade(blade, out.tuft.labels));
    }
    return out;
}

// Tip errors pooled over tufts: every single view's fit, and every track of one true blade
// fitted to its mean skeleton, as capture fits a track.
struct TipErrors {
    double singleSq_mm2 = 0.0, trackedSq_mm2 = 0.0;
    int single = 0, tracked = 0, trueBlades = 0, tracksOfOneBlade = 0;
    [[nodiscard]] double singleRms_mm() const {
        return single ? std::sqrt(singleSq_mm2 / single) : 0.0;
    }
    [[nodiscard]] double trackedRms_mm() const {
        return tracked ? std::sqrt(trackedSq_mm2 / tracked) : 0.0;
    }
};

inline void addTipErrors(const TrackedTuft& t, int fused, TipErrors& e,
                         const modeling::BladeFitParams& params = {}) {
    const auto tipError_mm = [&](const modeling::Skeleton& skeleton, int id) {
        const modeling::BladeFit fit = modeling::fitArchetype(skeleton, params);
        const glm::vec3 trueTip =
            t.tuft.tuft.blades.at(static_cast<std::size_t>(id - 1)).spineInCamera_m().v2;
        return glm::distance(fit.spineCamera_m.v2, trueTip) * 1e3;
    };
    const auto& skeletons = t.seen.skeletons;
    for (std::size_t i = 0; i < skeletons.size(); ++i)
        if (t.truth[i] != 0) {
            const double d = tipError_mm(skeletons[i].skeleton, t.truth[i]);
            e.singleSq_mm2 += d * d, ++e.single;
        }
    e.trueBlades += static_cast<int>(t.tuft.tuft.blades.size());
    for (const auto& track : modeling::trackBlades(skeletons)) {
        const bool oneBlade = t.trueBladeOfTrack(track) != 0;
        e.tracksOfOneBlade += oneBlade && static_cast<int>(track.size()) * fused == kTrackedFrames;
        if (!oneBlade) continue;
        const double d =
            tipError_mm(modeling::trackSkeleton(skeletons, track), t.truth[track.front()]);
        e.trackedSq_mm2 += d * d, ++e.tracked;
    }
}

}  // namespace meadow::test
