// One archetype per blade across fused groups (blade_tracks.h), against the simulated sensor's
// truth: a still tuft read in 4 groups of 3 fused frames, as `meadow capture` reads a recording
// of 12 frames. Each blade's observations must form one track, and the fit to the mean of a
// track's skeletons must land nearer the true tip than the single groups' fits do.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <iomanip>
#include <iostream>
#include <map>
#include <opencv2/core.hpp>
#include <span>

#include "meadow/capture/recurring_readings.h"
#include "meadow/capture/segmenter.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/blade_tracks.h"
#include "meadow/modeling/capture_pipeline.h"
#include "meadow/modeling/error.h"
#include "meadow/synth/simulated_sensor.h"
#include "meadow/synth/synthesize.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::modeling {
namespace {
using namespace synth;

constexpr int kGroups = 4;
constexpr int kFusedFrames = 3;
constexpr double kMinMaskShare = 0.5;  // as modeling_accuracy_test.cpp matches blades
// Tip RMS of the tracked fits against the single groups' fits, pooled over quadratic-, shrub-
// and bamboo-leaf (seed 1, 0.8 m): measured 0.62 (56 fits 4.87 mm, 14 tracks 3.02 mm), and each
// of the 14 blades one track of all 4 groups. Asserted with margin.
constexpr double kMaxTrackedToSingleTipRatio = 0.85;

struct Tuft {
    std::vector<capture::DepthFrame> frames;
    cv::Mat1w labels;
    SyntheticTuft tuft;
};

Tuft render(const std::string& presetName, float distance_m, std::uint64_t seed) {
    const SynthPreset* preset = findSynthPreset(presetName);
    if (!preset) throw std::invalid_argument("no preset " + presetName);
    TuftParams params;
    params.seed = seed;
    params.distance_m = distance_m;
    const TuftSpec spec = buildPresetSpec(*preset, params);
    synth::NoiseModel noise;
    noise.scale = preset->noiseMultiplier;
    const synth::SimulatedSensor sensor(spec.camera.intrinsics, noise);
    Tuft out;
    out.tuft = buildTuft(spec, 0);  // a still tuft: every frame draws only new noise
    for (int i = 0; i < kGroups * kFusedFrames; ++i) {
        const synth::SimulatedFrame sim =
            sensor.render(out.tuft.meshes(), synthFrameSeed(seed, static_cast<std::uint64_t>(i)));
        capture::DepthFrame frame;
        frame.depth_mm = sim.depth_mm;
        frame.intrinsics = spec.camera.intrinsics;
        frame.index = i;
        out.frames.push_back(std::move(frame));
        if (i == 0) out.labels = sim.labels;
    }
    return out;
}

// The true blade whose label holds most of the mask (and at least half of it), or 0.
int trueBladeOf(const capture::BladeContour& blade, const cv::Mat1w& labels) {
    std::map<int, int> votes;
    for (int v = 0; v < blade.mask.rows; ++v)
        for (int u = 0; u < blade.mask.cols; ++u)
            if (blade.mask(v, u))
                ++votes[labels(blade.maskOrigin_px.y + v, blade.maskOrigin_px.x + u)];
    int best = 0, bestVotes = 0;
    for (const auto& [id, n] : votes)
        if (n > bestVotes) best = id, bestVotes = n;
    return bestVotes >= kMinMaskShare * cv::countNonZero(blade.mask) ? best : 0;
}

struct TipErrors {
    double singleSq_mm2 = 0.0, trackedSq_mm2 = 0.0;
    int single = 0, tracked = 0, trueBlades = 0, tracksOfOneBlade = 0;
};

// `recurring`: the tip trails also see the readings recurring over all 12 frames, as capture's
// default (CaptureOptions::recurringFrames) does.
// `fused`: frames per segmentation (kFusedFrames, as capture's default; kGroups * kFusedFrames:
// one segmentation of all 12), fused as `segmenter` says.
// A rendered tuft's blades as capture sees them: each segmented blade's skeleton with the group
// it was seen in, and the true blade it is (0: none).
struct Observed {
    Tuft t;
    std::vector<BladeObservation> observations;
    std::vector<int> truth;
    // The true blade of a track when all its observations are of that one blade, else 0.
    [[nodiscard]] int trueBladeOfTrack(const std::vector<std::size_t>& track) const {
        for (const std::size_t i : track)
            if (truth[i] == 0 || truth[i] != truth[track.front()]) return 0;
        return truth[track.front()];
    }
};

Observed observe(const std::string& preset, float distance_m, bool recurring, std::uint64_t seed,
                 const capture::SegmenterParams& segmenterParams, int fused,
                 const BladeFitParams& params) {
    Observed o{render(preset, distance_m, seed), {}, {}};
    const Tuft& t = o.t;
    const capture::Segmenter segmenter(segmenterParams);
    const capture::RecurringReadings tips =
        recurring ? capture::recurringReadings(t.frames) : capture::RecurringReadings{};
    for (int g = 0; g < kGroups * kFusedFrames / fused; ++g) {
        const std::span<const capture::DepthFrame> group(t.frames.data() + g * fused,
                                                         static_cast<std::size_t>(fused));
        const capture::Segmentation seg = segmenter.segment(group, tips);
        for (std::size_t b = 0; b < seg.blades.size(); ++b) {
            const auto& flags = seg.blades[b].flags;
            if (std::any_of(flags.begin(), flags.end(), disqualifiesFromModelling)) continue;
            o.observations.push_back({g, segmentedBladeSkeleton(seg, b, group.front(), params)});
            o.truth.push_back(trueBladeOf(seg.blades[b], t.labels));
        }
    }
    return o;
}

void measure(const std::string& preset, float distance_m, bool recurring, TipErrors& e,
             std::uint64_t seed = 1, const capture::SegmenterParams& segmenterParams = {},
             int fused = kFusedFrames) {
    const BladeFitParams params;
    const Observed o = observe(preset, distance_m, recurring, seed, segmenterParams, fused, params);
    const Tuft& t = o.t;
    const auto& observations = o.observations;
    const auto& truth = o.truth;
    const auto tipError_mm = [&](const Skeleton& skeleton, int id) {
        const BladeFit fit = fitArchetype(skeleton, params);
        const glm::vec3 trueTip =
            t.tuft.blades.at(static_cast<std::size_t>(id - 1)).spineInCamera_m().v2;
        return glm::distance(fit.spineCamera_m.v2, trueTip) * 1e3;
    };
    for (std::size_t i = 0; i < observations.size(); ++i)
        if (truth[i] != 0) {
            const double d = tipError_mm(observations[i].skeleton, truth[i]);
            e.singleSq_mm2 += d * d, ++e.single;
        }
    const auto tracks = trackBlades(observations);
    e.trueBlades += static_cast<int>(t.tuft.blades.size());
    for (const auto& track : tracks) {
        const bool oneBlade = o.trueBladeOfTrack(track) != 0;
        e.tracksOfOneBlade += oneBlade && track.size() * fused == kGroups * kFusedFrames;
        if (!oneBlade) continue;
        // Fitted as capture fits a track.
        const double d = tipError_mm(trackSkeleton(observations, track), truth[track.front()]);
        e.trackedSq_mm2 += d * d, ++e.tracked;
    }
    std::cout << preset << ": " << tracks.size() << " tracks of " << observations.size()
              << " observations, " << t.tuft.blades.size() << " true blades\n";
}

TEST(BladeTracksAccuracy, EachBladeIsOneTrackAndItsMeanFitLandsNearerTheTrueTip) {
    TipErrors e;
    for (const std::string preset : {"quadratic-leaf", "shrub-leaf", "bamboo-leaf"})
        measure(preset, 0.8f, false, e);
    ASSERT_GT(e.single, 0);
    ASSERT_GT(e.tracked, 0);
    const double single = std::sqrt(e.singleSq_mm2 / e.single);
    const double tracked = std::sqrt(e.trackedSq_mm2 / e.tracked);
    std::cout << "tip RMS: single groups " << single << " mm (" << e.single << " fits), tracks "
              << tracked << " mm (" << e.tracked << " fits); " << e.tracksOfOneBlade << " of "
              << e.trueBlades << " true blades are one track of all " << kGroups << " groups\n";
    EXPECT_EQ(e.tracksOfOneBlade, e.trueBlades);
    EXPECT_LE(tracked, kMaxTrackedToSingleTipRatio * single);
}

// Sharp-tip's long thin point is dotted in every frame, in different pixels each time: the
// readings that recur over the 12 frames carry its tip trails farther toward the true tip.
// Seed 1, 0.6 / 0.8 / 1.0 m, tracked tip RMS: measured 8.11 -> 3.85 mm (0.47), 15 blades either
// way (5.19 mm when a trail tip's extension was the width trend's, capped at a fixed 0.025 of its
// length, and a group of readings kept one trail). Asserted with margin.
constexpr double kMaxRecurringToOwnTipRatio = 0.85;

TEST(BladeTracksAccuracy, ReadingsRecurringOverTheFramesBringSharpTipsNearerTheTruth) {
    TipErrors own, recurring;
    for (const float distance_m : {0.6f, 0.8f, 1.0f}) {
        measure("sharp-tip", distance_m, false, own);
        measure("sharp-tip", distance_m, true, recurring);
    }
    ASSERT_GT(own.tracked, 0);
    ASSERT_GT(recurring.tracked, 0);
    const double before = std::sqrt(own.trackedSq_mm2 / own.tracked);
    const double after = std::sqrt(recurring.trackedSq_mm2 / recurring.tracked);
    std::cout << "sharp-tip tracked tip RMS: own readings " << before << " mm (" << own.tracked
              << " blades), with recurring readings " << after << " mm (" << recurring.tracked
              << " blades)\n";
    EXPECT_EQ(recurring.tracked, own.tracked);
    EXPECT_LE(after, kMaxRecurringToOwnTipRatio * before);
}

// What is still unseen of a tip past its trail is a matter of pixels, so a trail tip is extended
// by how many pixels wide the blade is (blade_tip.h, extensionOnRecurringTrail_px): farther blades
// are extended farther. Shrub-leaf's long tapers need it most: seeds 1-2, 0.6 / 0.8 / 1.0 m, 12
// frames, tracked tip RMS measured 2.84 mm (3.56 mm with the width trend's extension capped at a
// fixed 0.025 of the length, which stopped its tips up to 9 mm short at 1.0 m). Asserted at the
// issue's target.
constexpr double kTipTarget_mm = 3.0;

TEST(BladeTracksAccuracy, ShrubLeavesFromTwelveFramesMeetTheTipTarget) {
    TipErrors e;
    for (const std::uint64_t seed : {1u, 2u})
        for (const float distance_m : {0.6f, 0.8f, 1.0f})
            measure("shrub-leaf", distance_m, true, e, seed);
    ASSERT_EQ(e.tracked, 30);
    const double rms = std::sqrt(e.trackedSq_mm2 / e.tracked);
    std::cout << "shrub-leaf tracked tip RMS with recurring readings: " << rms << " mm\n";
    EXPECT_LE(rms, kTipTarget_mm);
}

// One segmentation of all 12 frames fused by their nearest recurring readings (capture --fuse 12
// --fusion nearest-recurring) against capture's default, 4 groups of 3 frames fused by their
// median, each blade fitted to the mean of its 4 views; both with the tip trails' recurring
// readings. Seeds 1-2, 0.6 / 0.8 / 1.0 m. Printed for the README ("Fusing frames by recurring
// readings"), not asserted.
TEST(BladeTracksAccuracy, PrintsTwelveFramesFusedByRecurringReadingsAgainstFourGroups) {
    if (!std::getenv("MEADOW_TRACKS_FUSION")) GTEST_SKIP() << "set MEADOW_TRACKS_FUSION=1";
    capture::SegmenterParams recurringFusion;
    recurringFusion.fusion = capture::FusionMethod::NearestRecurring;
    std::cout << "| preset | 4 groups of 3, median: blades fitted, tip RMS (mm) | 1 group of 12, "
                 "nearest recurring |\n|---|---|---|\n";
    for (const std::string preset :
         {"slim-grass", "quadratic-leaf", "shrub-leaf", "bamboo-leaf", "sharp-tip"}) {
        TipErrors groups, one;
        for (const std::uint64_t seed : {1u, 2u})
            for (const float distance_m : {0.6f, 0.8f, 1.0f}) {
                measure(preset, distance_m, true, groups, seed);
                measure(preset, distance_m, true, one, seed, recurringFusion,
                        kGroups * kFusedFrames);
            }
        const auto rms = [](const TipErrors& x) {
            return x.tracked ? std::sqrt(x.trackedSq_mm2 / x.tracked) : 0.0;
        };
        std::cout << std::fixed << std::setprecision(2) << "| " << preset << " | " << groups.tracked
                  << " of " << groups.trueBlades << ", " << rms(groups) << " | " << one.tracked
                  << " of " << one.trueBlades << ", " << rms(one) << " |" << std::endl;
    }
}

double meanOf(const std::vector<double>& v) {
    double sum = 0.0;
    for (const double x : v) sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

// How far toward each true tip the sensor's readings reach over the 12 frames of a still tuft:
// walking the true spine back from its tip, the first point with a reading within 10 mm of its
// depth in a pixel of its 3 x 3 neighbourhood, in at least 1 and in at least 5 of the 12
// frames (5: what recurs, recurring_readings.h). What lies beyond is unseen: a tip can only be
// extrapolated there. Seeds 1-2, 0.6 / 0.8 / 1.0 m. Printed for the README ("Known failures",
// Tips), not asserted.
TEST(BladeTracksAccuracy, PrintsHowFarTheReadingsReachTowardEachTip) {
    if (!std::getenv("MEADOW_TIP_REACH")) GTEST_SKIP() << "set MEADOW_TIP_REACH=1";
    constexpr float kStep_m = 0.00025f, kOnSurface_m = 0.010f;
    constexpr int kRecurring = 5;
    std::cout << "| preset | blades | beyond what 1 frame reads: mean, max (mm) | beyond what 5 of "
                 "12 read: mean, max (mm) |\n|---|---|---|---|\n";
    for (const std::string preset : {"quadratic-leaf", "shrub-leaf", "bamboo-leaf", "sharp-tip"}) {
        std::vector<double> unseenAll, unseenRecurring;
        for (const std::uint64_t seed : {1u, 2u})
            for (const float distance_m : {0.6f, 0.8f, 1.0f}) {
                const Tuft t = render(preset, distance_m, seed);
                const capture::Intrinsics& k = t.frames.front().intrinsics;
                for (const SyntheticBlade& blade : t.tuft.blades) {
                    const QuadraticBezier spine = blade.spineInCamera_m();
                    const float length_m = spine.length();
                    const auto framesReading = [&](const glm::vec3& p) {
                        const glm::vec2 px = k.project(p);
                        const int u = static_cast<int>(std::lround(px.x)),
                                  v = static_cast<int>(std::lround(px.y));
                        int n = 0;
                        for (const auto& f : t.frames) {
                            bool read = false;
                            for (int dv = -1; dv <= 1 && !read; ++dv)
                                for (int du = -1; du <= 1 && !read; ++du) {
                                    const cv::Point q(u + du, v + dv);
                                    if (!cv::Rect({}, f.depth_mm.size()).contains(q)) continue;
                                    const std::uint16_t d = f.depth_mm(q);
                                    read = d > 0 && std::abs(d / 1000.f - p.z) <= kOnSurface_m;
                                }
                            n += read;
                        }
                        return n;
                    };
                    float reachAll = -1.f, reachRecurring = -1.f;
                    for (float back = 0.f; back < length_m && reachRecurring < 0.f;
                         back += kStep_m) {
                        const float fraction = 1.f - back / length_m;
                        const int n =
                            framesReading(spine.at(spine.parameterAtLengthFraction(fraction)));
                        if (n >= 1 && reachAll < 0.f) reachAll = back;
                        if (n >= kRecurring) reachRecurring = back;
                    }
                    unseenAll.push_back(1e3 * std::max(reachAll, 0.f));
                    unseenRecurring.push_back(1e3 * std::max(reachRecurring, 0.f));
                }
            }
        const auto max = [](const std::vector<double>& v) {
            return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
        };
        std::cout << std::fixed << std::setprecision(2) << "| " << preset << " | "
                  << unseenAll.size() << " | " << meanOf(unseenAll) << ", " << max(unseenAll)
                  << " | " << meanOf(unseenRecurring) << ", " << max(unseenRecurring) << " |"
                  << std::endl;
    }
}

// Where a tracked tip lands without any extension past what was seen, against the true tip,
// along the fitted spine's end tangent (positive: short of it) and across it. If each distance's
// mean shortfall were known and added, what would be left is the spread about it and the error
// across: what an extension by distance alone would leave; an extension must tell blade from
// blade to do better. Seeds 1-2, 0.6 / 0.8 / 1.0 m, 4 groups of 3 frames with the readings
// recurring over all 12. Printed for the README ("Known failures", Tips), not asserted.
TEST(BladeTracksAccuracy, PrintsTheTipsUnseenLengthAndItsSpread) {
    if (!std::getenv("MEADOW_TIP_REACH")) GTEST_SKIP() << "set MEADOW_TIP_REACH=1";
    BladeFitParams unextended;
    unextended.tip.enabled = false;
    std::cout << "| preset | tips | short along the tangent, mean at 0.6 / 0.8 / 1.0 m (mm) | "
                 "spread about those (SD, mm) | across (RMS, mm) | RMS with each distance's mean "
                 "added (mm) |\n|---|---|---|---|---|---|\n";
    for (const std::string preset : {"quadratic-leaf", "shrub-leaf", "bamboo-leaf", "sharp-tip"}) {
        std::vector<double> means;
        double spreadSq = 0.0, acrossSq = 0.0;
        int tips = 0;
        for (const float distance_m : {0.6f, 0.8f, 1.0f}) {
            std::vector<double> along;
            for (const std::uint64_t seed : {1u, 2u}) {
                const Observed o =
                    observe(preset, distance_m, true, seed, {}, kFusedFrames, unextended);
                for (const auto& track : trackBlades(o.observations)) {
                    const int id = o.trueBladeOfTrack(track);
                    if (id == 0) continue;
                    const QuadraticBezier fitted =
                        fitArchetype(trackSkeleton(o.observations, track), unextended)
                            .spineCamera_m;
                    const glm::vec3 miss =
                        o.t.tuft.blades.at(static_cast<std::size_t>(id - 1)).spineInCamera_m().v2 -
                        fitted.v2;
                    const glm::vec3 tangent = glm::normalize(fitted.tangent(1.f));
                    along.push_back(1e3 * glm::dot(miss, tangent));
                    acrossSq += 1e6 * glm::dot(miss - glm::dot(miss, tangent) * tangent,
                                               miss - glm::dot(miss, tangent) * tangent);
                }
            }
            const double mean = meanOf(along);
            for (const double a : along) spreadSq += (a - mean) * (a - mean);
            means.push_back(mean);
            tips += static_cast<int>(along.size());
        }
        std::cout << std::fixed << std::setprecision(2) << "| " << preset << " | " << tips << " | "
                  << means[0] << " / " << means[1] << " / " << means[2] << " | "
                  << std::sqrt(spreadSq / tips) << " | " << std::sqrt(acrossSq / tips) << " | "
                  << std::sqrt((spreadSq + acrossSq) / tips) << " |" << std::endl;
    }
}

}  // namespace
}  // namespace meadow::modeling
