// End-to-end modeling accuracy against the simulated sensor's ground truth: synth's blade-type
// presets at nominal noise, one frame, 0.6 / 0.8 / 1.0 m -> Segmenter -> the fit capture makes
// of each blade it vouches for (rooted at its tuft's base, continued past its visible tip),
// compared with the true spine and width profile (synth::bladeError). A segmented blade is the
// true blade whose label holds the majority of its mask (at least half of it).
//
// Targets: tip error <= 3 mm RMS, height error <= 2 % (mean), width-profile MAE <= 15 % of the
// blade's max width (mean). From one frame they are not met (docs/capture.md, "Where it fails";
// docs/measurements/modeling_accuracy.md); a blade fitted to the mean of its views over several
// groups comes nearer (blade_tracks_accuracy_test.cpp). Asserted here, on each of seeds 1-3:
// at least a third of the true blades fitted, and on the four leaf presets (slim grass is
// over-segmented) bounds with margin over today's accuracy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "meadow/capture/segmenter.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/capture_pipeline.h"
#include "meadow/modeling/error.h"
#include "meadow/synth/blade_error.h"
#include "meadow/synth/blade_match.h"
#include "meadow/synth/rendered_tuft.h"

namespace meadow::modeling {
namespace {

const std::vector<std::string> kBladeTypePresets{"slim-grass", "quadratic-leaf", "shrub-leaf",
                                                 "bamboo-leaf", "sharp-tip"};
constexpr float kMaxWidthMaeFraction = 0.15f;
constexpr float kMaxLeafV0Error_mm = 8.f;
constexpr float kMaxLeafHeightError = 0.05f;
constexpr float kMaxLeafTipRms_mm = 8.f;

struct Score {
    int truth = 0, fitted = 0;
    double tipSq_mm2 = 0.0, heightError = 0.0, widthFraction = 0.0, v0_mm = 0.0;
    void add(const Score& o) {
        truth += o.truth, fitted += o.fitted;
        tipSq_mm2 += o.tipSq_mm2, heightError += o.heightError;
        widthFraction += o.widthFraction, v0_mm += o.v0_mm;
    }
    [[nodiscard]] double tipRms_mm() const { return fitted ? std::sqrt(tipSq_mm2 / fitted) : 0.0; }
    [[nodiscard]] double meanHeightError() const { return fitted ? heightError / fitted : 0.0; }
    [[nodiscard]] double meanWidthFraction() const { return fitted ? widthFraction / fitted : 0.0; }
    [[nodiscard]] double meanV0_mm() const { return fitted ? v0_mm / fitted : 0.0; }
};

std::ostream& operator<<(std::ostream& out, const Score& s) {
    return out << "fitted " << s.fitted << " of " << s.truth << ", v0 error " << s.meanV0_mm()
               << " mm, tip RMS " << s.tipRms_mm() << " mm, height error "
               << 100.0 * s.meanHeightError() << " %, width MAE " << 100.0 * s.meanWidthFraction()
               << " % of max width";
}

// The sensor noise these bounds were set on: frame 0 drawn with the seed itself.
std::uint64_t boundNoiseSeed(std::uint64_t seed, int) { return seed; }

Score run(const std::string& preset, float distance_m, std::uint64_t seed,
          const capture::SegmenterParams& params = {}) {
    const synth::RenderedTuft tuft =
        synth::renderTuft(preset, 1.f, seed, distance_m, 1, {}, boundNoiseSeed);
    const capture::DepthFrame& frame = tuft.frames.front();
    const capture::Segmentation seg = capture::Segmenter(params).segment(frame);
    Score score;
    score.truth = static_cast<int>(tuft.tuft.blades.size());
    for (std::size_t index = 0; index < seg.blades.size(); ++index) {
        const capture::BladeContour& blade = seg.blades[index];
        if (std::any_of(blade.flags.begin(), blade.flags.end(), disqualifiesFromModelling))
            continue;
        const int id = synth::majorityTrueBlade(blade, tuft.labels);
        if (id == 0) continue;
        BladeFit fit;
        try {
            fit = fitSegmentedBlade(seg, index, frame);
        } catch (const ModelingError&) {
            continue;
        }
        const synth::BladeError e =
            synth::bladeError(fit, tuft.tuft.blades.at(static_cast<std::size_t>(id - 1)));
        ++score.fitted;
        score.tipSq_mm2 += e.v2_mm * e.v2_mm;
        score.heightError += std::abs(e.heightError);
        score.widthFraction += e.widthMaeFraction;
        score.v0_mm += e.v0_mm;
    }
    return score;
}

TEST(ModelingAccuracy, LeafBladesAreRootedAtTheirTrueRootAtNominalNoise) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        Score all, leaves;
        for (const std::string& preset : kBladeTypePresets) {
            Score perPreset;
            for (const float distance_m : {0.6f, 0.8f, 1.0f})
                perPreset.add(run(preset, distance_m, seed));
            all.add(perPreset);
            if (preset != "slim-grass") leaves.add(perPreset);
        }
        EXPECT_LE(leaves.meanV0_mm(), kMaxLeafV0Error_mm) << "leaves: " << leaves;
        EXPECT_LE(leaves.meanHeightError(), kMaxLeafHeightError) << "leaves: " << leaves;
        EXPECT_LE(leaves.tipRms_mm(), kMaxLeafTipRms_mm) << "leaves: " << leaves;
        EXPECT_LE(leaves.meanWidthFraction(), kMaxWidthMaeFraction) << "leaves: " << leaves;
        EXPECT_GE(3 * all.fitted, all.truth) << "all: " << all;
    }
}

// A grass tuft in a pot is captured with --subject potted-plant: cut by the stem graph, its
// blades fan from the foot, the tangle of skeleton junctions where they meet. Their heights
// are held less tightly than the contour partition's above (docs/capture.md, partition by the
// stem), but a foot that loses the blades' bases to a short stem goes past this bound.
constexpr float kMaxStemGraphTuftHeightError = 0.22f;

TEST(ModelingAccuracy, TuftBladesCutByTheStemGraphKeepTheirHeight) {
    capture::SegmenterParams potted;
    potted.setSubject(capture::Subject::PottedPlant);
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        Score leaves;
        for (const std::string& preset : kBladeTypePresets)
            if (preset != "slim-grass")
                for (const float distance_m : {0.6f, 0.8f, 1.0f})
                    leaves.add(run(preset, distance_m, seed, potted));
        EXPECT_LE(leaves.meanHeightError(), kMaxStemGraphTuftHeightError) << "leaves: " << leaves;
    }
}

}  // namespace
}  // namespace meadow::modeling
