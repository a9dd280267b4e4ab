// End-to-end modeling accuracy against the simulated sensor's ground truth: synthetic tuft
// presets -> SimulatedSensor (nominal noise) -> Segmenter -> fitBlade, compared with the true
// spines and width profiles. A segmented blade is matched to the true blade whose label holds the
// majority of its mask (and at least half of it); flagged blades are skipped, as capture does.
// Targets on the five blade-type presets at 0.6, 0.8 and 1.0 m: tip position error <= 3 mm RMS,
// height error <= 2 % (mean), width-profile MAE <= 15 % of the blade's max width (mean).
//
// Blades are fitted as capture fits them (fitSegmentedBlade): rooted at their cluster's base
// point (the segmenter cuts a tuft's blades at their fork; blade_root.h), with the end-outward
// depth rejection of skeleton.cpp at thin tips, and continued past their visible tip to where
// their tapering width reaches zero (blade_tip.h).
//
// MEASURED: NOT MET (see the README, "Modeling accuracy"). Rooting brought the fitted v0 to the
// true root (mean 4.6-12 mm on the four leaf presets, was 30-45 mm) and the height error down
// (6.5-17 %, was 23-31 %); width MAE 10-21 % (was 15.5-27 %). The segmented tip ends at ~90 % of
// the true length (thin tips fall below the sensor's resolution); the tip extension brings the
// fitted tip to s ~ 1.0 and, on the four leaf presets, tip RMS 4.2-17 mm (was 7.8-41), height
// error 3.3-4.9 % (was 6.9-17 %), width MAE 7.4-15 % (was 10-20 %). Still missing: the extension
// is straight, so a drooping tip (shrub leaf) ends off the true curve; slim grass is
// over-segmented (several pieces per blade, each rooted).
// The base now sits on the cluster's lowest row, or on the ground plane just below it: the
// fitted v0 was 3.3-4.8 mm above the true root (up to 20 mm), now within about 1 mm vertically.
// The segmenter links tips back that lateral noise had dotted (tip trails), so less of the tip
// is extrapolated: tip RMS 5.7-6.6 mm on the four leaf presets (seeds 1-3), height 1.9-3.6 %.
// The tip fitted with the spine instead of pinned to the skeleton's last point: 5.4-5.6 mm.
// Asserted with margin: at least a third of the true blades fitted; on the four leaf presets
// (slim grass excluded, see above) the mean v0 error <= 8 mm, the mean height error <= 5 %, the
// tip RMS <= 8 mm and the mean width MAE <= 15 % of max width. The other targets are printed.
// These are single views (one fused group each). Fitting each blade once to the mean of its views
// over several groups (blade_tracks.h) takes the noise part of the tip error down:
// blade_tracks_accuracy_test.cpp, and the README's "One archetype per blade".
// MEADOW_MODELING_TABLE=1 prints the per-preset table; MEADOW_MODELING_VERBOSE=1 every blade;
// The bounds hold on each of seeds 1-3; MEADOW_MODELING_SEED=N runs seed N alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <glm/geometric.hpp>
#include <iomanip>
#include <iostream>
#include <map>
#include <opencv2/core.hpp>

#include "meadow/capture/segmenter.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/capture_pipeline.h"
#include "meadow/modeling/error.h"
#include "meadow/synth/simulated_sensor.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::modeling {
namespace {
using namespace synth;

const std::vector<std::string> kBladeTypePresets{"slim-grass", "quadratic-leaf", "shrub-leaf",
                                                 "bamboo-leaf", "sharp-tip"};
constexpr float kMaxTipRms_mm = 3.f;
constexpr float kMaxHeightError = 0.02f;
constexpr float kMaxWidthMaeFraction = 0.15f;
constexpr double kMinMaskShare = 0.5;  // share of a segmented mask on its true label to match
constexpr int kWidthComparisonSamples = 50;
// Asserted on the leaf presets (all but slim grass): measured 6.8 mm and 11.2 % with the segmenter
// of a6b89d8, 10.3 mm and 14.8 % with its edge smoothing under way; 36 mm and 27 % unrooted.
// With the base on the cluster's lowest row and dropped onto the ground plane (blade_root.h):
// mean v0 error 3.8 mm (seed 1; seeds 2 and 3: 6.6 and 6.4 mm), was 7.3 / 8.5 / 9.8 mm. Seed 2
// measures 8.1 mm since the shorter tip extension: one fragment of a blade cut in two is no
// longer rooted. With the edge smoothed along the contour: 3.7 / 8.0 / 6.3 mm. With the spine's
// root fitted instead of pinned to the base point (SpineEnds::Fitted): 3.0 / 6.6 / 5.0 mm. With a
// tuft seen from close up no longer skipped as scenery (shrub-leaf at 0.6 m): 3.0 / 6.5 / 4.8 mm.
constexpr float kMaxLeafV0Error_mm = 8.f;
// With the tip extension (blade_tip.h): measured 4.2 %, 12.9 mm and 10.3 % (seed 1); without it
// 11.8 %, 24.8 mm and 14.6 %. With the segmenter's tip trails, the readings held to the
// tuft's depth range and the shorter extension caps (blade_tip.h): height error
// 1.9 / 3.6 / 3.3 % and tip RMS 6.1 / 5.7 / 6.6 mm (seeds 1 / 2 / 3), were 3.9 / 3.7 / 5.7 %
// and 12.2 / 8.2 / 18.0 mm. With the edge smoothed along the contour: 1.8 / 3.6 / 3.2 % and
// 5.9 / 5.8 / 6.2 mm. With the tip fitted with the spine (SpineEnds::RootAtFirstPoint): 1.8 / 3.6 /
// 3.1 % and 5.4 / 5.6 / 5.4 mm, so the tip bound came down from 10 to 8 mm; with the root piece
// and the tip extension left out of the spine fit, 1.8 / 3.6 / 3.1 % and 5.4 / 5.5 / 5.3 mm.
constexpr float kMaxLeafHeightError = 0.05f;
constexpr float kMaxLeafTipRms_mm = 8.f;

// Seeds 1-3, or the one MEADOW_MODELING_SEED names.
std::vector<std::uint64_t> seedsFromEnvironment() {
    const char* text = std::getenv("MEADOW_MODELING_SEED");
    if (text) return {std::strtoull(text, nullptr, 10)};
    return {1, 2, 3};
}

struct Score {
    int truth = 0, fitted = 0, failed = 0;
    double tipSq_mm2 = 0.0, heightError = 0.0, widthFraction = 0.0, spineRms_mm = 0.0;
    double v0_mm = 0.0;              // sum of the fitted root's distance to the true root
    std::vector<float> offSpine_mm;  // per blade: largest distance of the fitted spine to the truth
    std::vector<float> baseFraction, tipFraction;  // where the fitted ends lie on the true spine
    void add(const Score& o) {
        offSpine_mm.insert(offSpine_mm.end(), o.offSpine_mm.begin(), o.offSpine_mm.end());
        baseFraction.insert(baseFraction.end(), o.baseFraction.begin(), o.baseFraction.end());
        tipFraction.insert(tipFraction.end(), o.tipFraction.begin(), o.tipFraction.end());
        truth += o.truth, fitted += o.fitted, failed += o.failed;
        tipSq_mm2 += o.tipSq_mm2, heightError += o.heightError, widthFraction += o.widthFraction;
        spineRms_mm += o.spineRms_mm, v0_mm += o.v0_mm;
    }
    static float median(std::vector<float> v) {
        if (v.empty()) return 0.f;
        std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
        return v[v.size() / 2];
    }
    [[nodiscard]] double tipRms_mm() const { return fitted ? std::sqrt(tipSq_mm2 / fitted) : 0.0; }
    [[nodiscard]] double meanHeightError() const { return fitted ? heightError / fitted : 0.0; }
    [[nodiscard]] double meanWidthFraction() const { return fitted ? widthFraction / fitted : 0.0; }
    [[nodiscard]] double meanV0_mm() const { return fitted ? v0_mm / fitted : 0.0; }
};

Score run(const std::string& presetName, float distance_m, std::uint64_t seed) {
    const SynthPreset* preset = findSynthPreset(presetName);
    if (!preset) throw std::invalid_argument("no preset " + presetName);
    TuftParams tp;
    tp.seed = seed;
    tp.distance_m = distance_m;
    const TuftSpec spec = buildPresetSpec(*preset, tp);
    const SyntheticTuft tuft = buildTuft(spec, 0);
    synth::NoiseModel noise;
    noise.scale = preset->noiseMultiplier;
    const synth::SimulatedSensor sensor(spec.camera.intrinsics, noise);
    const synth::SimulatedFrame sim = sensor.render(tuft.meshes(), seed);
    capture::DepthFrame frame;
    frame.depth_mm = sim.depth_mm;
    frame.intrinsics = spec.camera.intrinsics;
    const capture::Segmentation seg = capture::Segmenter().segment(frame);
    if (const char* folder = std::getenv("MEADOW_MODELING_DEBUG"))
        capture::writeDebugOverlay(
            std::filesystem::path(folder) / (presetName + "_" + std::to_string(distance_m) + "m_s" +
                                             std::to_string(seed) + ".png"),
            frame, seg);

    Score score;
    score.truth = static_cast<int>(tuft.blades.size());
    for (std::size_t index = 0; index < seg.blades.size(); ++index) {
        const capture::BladeContour& blade = seg.blades[index];
        if (std::any_of(blade.flags.begin(), blade.flags.end(), disqualifiesFromModelling))
            continue;
        // Majority true label under the mask.
        std::map<int, int> votes;
        for (int v = 0; v < blade.mask.rows; ++v)
            for (int u = 0; u < blade.mask.cols; ++u)
                if (blade.mask(v, u))
                    ++votes[sim.labels(blade.maskOrigin_px.y + v, blade.maskOrigin_px.x + u)];
        const auto best =
            std::max_element(votes.begin(), votes.end(),
                             [](const auto& a, const auto& b) { return a.second < b.second; });
        const int area = cv::countNonZero(blade.mask);
        if (best == votes.end() || best->first == 0 || best->second < kMinMaskShare * area)
            continue;
        const SyntheticBlade& truth = tuft.blades.at(static_cast<std::size_t>(best->first - 1));
        BladeFit fit;
        try {
            fit = fitSegmentedBlade(seg, index, frame);
        } catch (const ModelingError&) {
            ++score.failed;
            continue;
        }
        const QuadraticBezier truthSpine = truth.spineInCamera_m();
        const float tip_mm = glm::distance(fit.spineCamera_m.v2, truthSpine.v2) * 1e3f;
        const float trueHeight = truthSpine.length();
        double widthSum = 0.0;
        for (int i = 0; i <= kWidthComparisonSamples; ++i) {
            const float s = static_cast<float>(i) / kWidthComparisonSamples;
            widthSum += std::abs(fit.archetype.width.at(s) - truth.archetype.width.at(s));
        }
        ++score.fitted;
        score.tipSq_mm2 += tip_mm * tip_mm;
        score.heightError += std::abs(fit.archetype.height_m() - trueHeight) / trueHeight;
        score.widthFraction +=
            widthSum / (kWidthComparisonSamples + 1) / truth.archetype.width.maxWidth_m();
        score.spineRms_mm += fit.archetype.fit.spineRms_mm;
        score.v0_mm += glm::distance(fit.spineCamera_m.v0, truthSpine.v0) * 1e3f;
        // Where the fitted ends lie on the true spine: arc fraction of the closest point and the
        // distance off the spine (separates a hidden / cut base from a fit error).
        const auto onTruth = [&](const glm::vec3& p) {
            float bestD = 1e30f, bestT = 0.f;
            for (int i = 0; i <= 1000; ++i) {
                const float d = glm::distance(p, truthSpine.at(i / 1000.f));
                if (d < bestD) bestD = d, bestT = i / 1000.f;
            }
            return std::pair<float, float>{truthSpine.lengthTo(bestT) / trueHeight, bestD * 1e3f};
        };
        const auto [baseFraction, baseOff_mm] = onTruth(fit.spineCamera_m.v0);
        const auto [tipFraction, tipOff_mm] = onTruth(fit.spineCamera_m.v2);
        float offSpine_mm = 0.f;
        for (int i = 0; i <= kWidthComparisonSamples; ++i)
            offSpine_mm = std::max(
                offSpine_mm,
                onTruth(fit.spineCamera_m.at(static_cast<float>(i) / kWidthComparisonSamples))
                    .second);
        score.offSpine_mm.push_back(offSpine_mm);
        score.baseFraction.push_back(baseFraction);
        score.tipFraction.push_back(tipFraction);
        if (std::getenv("MEADOW_MODELING_VERBOSE"))
            std::cout << "   base at s=" << baseFraction << " (" << baseOff_mm
                      << " mm off), tip at s=" << tipFraction << " (" << tipOff_mm
                      << " mm off), spine max distance to truth " << offSpine_mm << " mm\n";
        if (std::getenv("MEADOW_MODELING_VERBOSE"))
            std::cout << presetName << " d " << distance_m << " blade " << best->first << " tip "
                      << tip_mm << " mm, height " << fit.archetype.height_m() << " vs "
                      << trueHeight << ", width MAE "
                      << widthSum / (kWidthComparisonSamples + 1) * 1e3 << " mm of max "
                      << truth.archetype.width.maxWidth_m() * 1e3 << " mm\n";
    }
    return score;
}

void checkSeed(std::uint64_t seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::cout << "seed " << seed << '\n';
    const bool table = std::getenv("MEADOW_MODELING_TABLE") != nullptr;
    if (table)
        std::cout << "| preset | distance | blades fitted / true | v0 error (mm, mean) | tip RMS "
                     "(mm) | height error | "
                     "width MAE / max "
                     "width | spine RMS (mm) | fitted spine to true (median, mm) | base s / tip s "
                     "(median) "
                     "|\n|---|---|---|---|---|---|---|---|---|---|\n";
    Score all, leaves;
    for (const std::string& preset : kBladeTypePresets) {
        Score perPreset;
        for (const float distance_m : {0.6f, 0.8f, 1.0f}) {
            const Score s = run(preset, distance_m, seed);
            perPreset.add(s);
            if (table)
                std::cout << std::fixed << std::setprecision(3) << "| " << preset << " | "
                          << distance_m << " | " << s.fitted << " / " << s.truth << " | "
                          << s.meanV0_mm() << " | " << s.tipRms_mm() << " | "
                          << 100.0 * s.meanHeightError() << " % | " << 100.0 * s.meanWidthFraction()
                          << " % | " << (s.fitted ? s.spineRms_mm / s.fitted : 0.0) << " | "
                          << Score::median(s.offSpine_mm) << " | " << Score::median(s.baseFraction)
                          << " / " << Score::median(s.tipFraction) << " |\n";
        }
        std::cout << "  " << preset << ": fitted " << perPreset.fitted << "/" << perPreset.truth
                  << ", v0 error " << perPreset.meanV0_mm() << " mm, tip RMS "
                  << perPreset.tipRms_mm() << " mm, height error "
                  << 100.0 * perPreset.meanHeightError() << " %, width MAE "
                  << 100.0 * perPreset.meanWidthFraction() << " % of max width\n";
        all.add(perPreset);
        if (preset != "slim-grass") leaves.add(perPreset);
    }
    EXPECT_LE(leaves.meanV0_mm(), kMaxLeafV0Error_mm);
    EXPECT_LE(leaves.meanHeightError(), kMaxLeafHeightError);
    EXPECT_LE(leaves.tipRms_mm(), kMaxLeafTipRms_mm);
    EXPECT_LE(leaves.meanWidthFraction(), kMaxWidthMaeFraction);
    EXPECT_GE(3 * all.fitted,
              all.truth);  // measured 59 of 87 (57 of the 60 leaves): most slim-grass pieces
                           // are flagged too-thin upstream, the rest unmatched
    std::cout << "  targets (not asserted, see the header): tip RMS <= " << kMaxTipRms_mm
              << " mm, height error <= " << 100.f * kMaxHeightError
              << " %, width MAE <= " << 100.f * kMaxWidthMaeFraction << " %\n";
    std::cout << "  leaves: fitted " << leaves.fitted << "/" << leaves.truth << ", v0 error "
              << leaves.meanV0_mm() << " mm, tip RMS " << leaves.tipRms_mm() << " mm, height error "
              << 100.0 * leaves.meanHeightError() << " %, width MAE "
              << 100.0 * leaves.meanWidthFraction() << " % of max width\n";
    std::cout << "  all: median fitted-spine-to-truth " << Score::median(all.offSpine_mm)
              << " mm, base at s " << Score::median(all.baseFraction) << ", tip at s "
              << Score::median(all.tipFraction) << "; fitted " << all.fitted << "/" << all.truth
              << ", v0 error " << all.meanV0_mm() << " mm, tip RMS " << all.tipRms_mm()
              << " mm, height error " << 100.0 * all.meanHeightError() << " %, width MAE "
              << 100.0 * all.meanWidthFraction() << " % of max width\n";
}

TEST(ModelingAccuracy, LeafBladesAreRootedAtTheirTrueRootAtNominalNoiseAndTargetsAreReported) {
    for (const std::uint64_t seed : seedsFromEnvironment()) checkSeed(seed);
}

}  // namespace
}  // namespace meadow::modeling
