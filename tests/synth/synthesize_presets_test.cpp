// Every preset of `meadow synth`, written to disk and read back through the recording reader:
// the files agree with each other and with the meshes they were rendered from.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "meadow/capture/depth_source.h"
#include "meadow/synth/simulated_sensor.h"
#include "meadow/synth/synthesize.h"
#include "meadow/synth/synthetic_tuft.h"
#include "support/truth_oracles.h"

namespace meadow::synth {
using namespace modeling;
namespace {

namespace fs = std::filesystem;

// Frames per preset: two, so the wind preset shows motion between them; more only costs time.
constexpr int kFrames = 2;
// A reading agrees with the truth mesh within 4 sigma of the axial noise, half a disparity step
// and the millimetre rounding; at least this share of interior blade pixels must.
constexpr float kSigmas = 4.f;
constexpr float kMillimetreRounding_m = 0.0005f;
constexpr double kMinAgreeingShare = 0.99;
constexpr int kMinCheckedPixels = 40;  // fewer judge nothing
// Lateral noise displaces a reading by N(0, lateral_px) in x and y; 3 sigma bounds its reach.
constexpr float kLateralReachSigmas = 3.f;

struct Agreement {
    int checked = 0, within = 0;
    float worstError_mm = 0.f;
};

// Labelled interior pixels of `labels` whose reading in `depth_mm` is consistent with the
// labelled blade's mesh under the sensor's noise model.
Agreement depthAgreesWithMeshes(const cv::Mat1w& depth_mm, const cv::Mat1w& labels,
                                const SyntheticTuft& tuft, const capture::Intrinsics& k,
                                const synth::NoiseModel& noise, int radius) {
    std::vector<TriangleMesh> meshes;
    for (const SyntheticBlade& b : tuft.blades) meshes.push_back(b.meshInCamera());
    Agreement a;
    for (int v = 0; v < labels.rows; ++v)
        for (int u = 0; u < labels.cols; ++u) {
            const int id = labels(v, u);
            if (id == 0 || depth_mm(v, u) == 0 || !test::interior(labels, u, v, radius)) continue;
            if (id > static_cast<int>(meshes.size())) continue;  // counted by the id check
            const test::RayHit hit = test::rayHit(meshes[static_cast<size_t>(id - 1)], k, u, v);
            ++a.checked;
            if (!std::isfinite(hit.depth_m)) continue;  // labelled, but the ray misses: disagree
            const float tolerance_m =
                kSigmas * noise.scale * synth::axialSigma_m(hit.depth_m, hit.incidence_rad) +
                0.5f *
                    synth::disparityStep_m(hit.depth_m, k.fx_px, noise.baseline_m, noise.subpixel) +
                kMillimetreRounding_m;
            const float error_m =
                std::abs(static_cast<float>(depth_mm(v, u)) * 1e-3f - hit.depth_m);
            if (error_m <= tolerance_m)
                ++a.within;
            else
                a.worstError_mm = std::max(a.worstError_mm, error_m * 1e3f);
        }
    return a;
}

int lateralReach_px(const synth::NoiseModel& noise) {
    return static_cast<int>(std::ceil(kLateralReachSigmas * noise.scale * noise.lateral_px));
}

// Blade pixels whose noisy reading lies within [min, max] of the exact surface depths within
// lateral reach, widened by the axial and quantisation tolerance: lateral noise shows a nearby
// surface, a flying pixel a depth between two of them.
Agreement withinLateralReach(const cv::Mat1w& noisy_mm, const cv::Mat1f& exact_m,
                             const cv::Mat1w& labels, const synth::NoiseModel& noise,
                             const capture::Intrinsics& k) {
    // A flying pixel mixes its own reading with a 4-neighbour's surface, and both can be
    // displaced by lateral noise: twice its reach and one more pixel.
    const int r = 2 * lateralReach_px(noise) + 1;
    const cv::Mat window = cv::getStructuringElement(cv::MORPH_RECT, {2 * r + 1, 2 * r + 1});
    cv::Mat1f exactOrFar = exact_m.clone();
    exactOrFar.setTo(std::numeric_limits<float>::max(), exact_m <= 0.f);
    cv::Mat1f lo_m, hi_m;
    cv::erode(exactOrFar, lo_m, window);
    cv::dilate(exact_m, hi_m, window);
    // Grazing incidence is not known here; the axial tolerance takes the head-on value.
    const auto tolerance_m = [&](float z_m) {
        return kSigmas * noise.scale * synth::axialSigma_m(z_m, 0.f) +
               synth::disparityStep_m(z_m, k.fx_px, noise.baseline_m, noise.subpixel) +
               kMillimetreRounding_m;
    };
    Agreement a;
    for (int v = 0; v < labels.rows; ++v)
        for (int u = 0; u < labels.cols; ++u) {
            if (labels(v, u) == 0 || noisy_mm(v, u) == 0) continue;
            ++a.checked;
            if (!(hi_m(v, u) > 0.f)) continue;  // a reading where no surface is in reach
            const float z_m = static_cast<float>(noisy_mm(v, u)) * 1e-3f;
            if (z_m >= lo_m(v, u) - tolerance_m(lo_m(v, u)) &&
                z_m <= hi_m(v, u) + tolerance_m(hi_m(v, u)))
                ++a.within;
        }
    return a;
}

// With noise, every blade reading must also lie within the exact depths in reach of lateral
// noise (widened by the axial tolerance): what a displaced or flying pixel can show.
void writeReadAndCheck(const SynthPreset& preset, float noiseScale, int interiorRadius_px) {
    const fs::path out = fs::temp_directory_path() / ("meadow_every_preset_" + preset.name);
    fs::remove_all(out);
    SynthOptions options;
    options.preset = preset.name;
    options.out = out;
    options.frames = kFrames;
    options.seed = 3;
    options.noiseScale = noiseScale;
    const SynthTruth written = synthesize(options);
    const std::string what = preset.name + " at noise " + std::to_string(noiseScale).substr(0, 3);

    // The truth file is what synthesize returned.
    const SynthTruth truth = readSynthTruth(out / "truth" / "blades.json");
    ASSERT_EQ(truth, written) << what;
    ASSERT_EQ(truth.frames.size(), static_cast<size_t>(kFrames)) << what;

    // The recording reads back through the reader every other command uses.
    const auto source = capture::openDepthSource(out.string());
    EXPECT_EQ(source->info().frameCount, kFrames) << what;
    EXPECT_EQ(source->info().intrinsics, truth.intrinsics) << what;

    // The meshes it was rendered from, rebuilt from the preset and the same seed.
    TuftSpec spec = buildPresetSpec(preset, {.seed = options.seed});
    spec.wind.frameRate_hz = static_cast<float>(source->info().frameRate_hz);
    synth::NoiseModel noise;
    noise.scale = truth.sensorNoiseScale;
    EXPECT_FLOAT_EQ(noise.scale, noiseScale * preset.noiseMultiplier) << what;

    for (int f = 0; f < kFrames; ++f) {
        const std::optional<capture::DepthFrame> frame = source->next();
        ASSERT_TRUE(frame) << what << ": frame " << f << " missing";
        const SynthTruthFrame& truthFrame = truth.frames[static_cast<size_t>(f)];
        const SyntheticTuft tuft = buildTuft(spec, f);
        EXPECT_EQ(truthOfFrame(tuft, f), truthFrame) << what << " frame " << f;

        const cv::Mat1w labels =
            cv::imread((out / "truth" / truthFrame.labels).string(), cv::IMREAD_UNCHANGED);
        ASSERT_EQ(labels.size(), frame->depth_mm.size()) << truthFrame.labels;

        // Rendered in memory with synthFrameSeed, the frame is the one written, reading for
        // reading: the trade-off bench measures the recordings `meadow synth` makes.
        const synth::SimulatedFrame again =
            synth::SimulatedSensor(truth.intrinsics, noise)
                .render(tuft.meshes(), synthFrameSeed(options.seed, static_cast<std::uint64_t>(f)));
        EXPECT_EQ(cv::countNonZero(again.depth_mm != frame->depth_mm), 0) << what << " frame " << f;

        // Ids in the label image are exactly the truth's blades (all visible) and background.
        std::set<int> truthIds{0}, seen;
        for (const SynthTruthBlade& b : truthFrame.blades) truthIds.insert(b.id);
        for (int v = 0; v < labels.rows; ++v)
            for (int u = 0; u < labels.cols; ++u) seen.insert(labels(v, u));
        EXPECT_EQ(seen, truthIds) << what << " frame " << f;

        const Agreement a = depthAgreesWithMeshes(frame->depth_mm, labels, tuft, truth.intrinsics,
                                                  noise, interiorRadius_px);
        // Blades narrower than the interior margin (slim-grass, thin under noise) have no
        // interior; the noise-free pass and the reach test judge them.
        if (a.checked >= kMinCheckedPixels || noise.scale == 0.f) {
            EXPECT_GE(a.within, kMinAgreeingShare * a.checked)
                << what << " frame " << f << ": " << a.within << " of " << a.checked
                << " blade readings agree with the mesh; worst error " << a.worstError_mm << " mm";
        }
        if (noise.scale == 0.f) {
            EXPECT_GE(a.checked, kMinCheckedPixels) << what << ": too few blade pixels to judge";
        } else {
            // The exact depth of the nearest surface, as the sensor sees it before any noise.
            const cv::Mat1f exact_m =
                synth::SimulatedSensor(truth.intrinsics, noise).render(tuft.meshes(), 0).exact_m;
            const Agreement r =
                withinLateralReach(frame->depth_mm, exact_m, labels, noise, truth.intrinsics);
            EXPECT_GE(r.checked, kMinCheckedPixels) << what << ": too few blade pixels to judge";
            EXPECT_GE(r.within, kMinAgreeingShare * r.checked)
                << what << " frame " << f << ": " << r.within << " of " << r.checked
                << " blade readings lie within the exact depths in lateral reach";
        }
    }
    EXPECT_FALSE(source->next()) << what << ": more frames than recording.json says";
    if (preset.name == "wind") {
        EXPECT_NE(truth.frames[0].blades[0].spineCamera_m.v2,
                  truth.frames[1].blades[0].spineCamera_m.v2)
            << "the wind preset's tips move between frames";
    }
    fs::remove_all(out);
}

class EveryPreset : public ::testing::TestWithParam<std::string> {};

// Without noise every labelled pixel reads its own blade (quantisation and rounding aside).
// With the preset's noise, pixels beyond the reach of lateral noise (3 sigma of
// N(0, lateral_px)) from any silhouette read their blade within the axial noise, and every
// blade reading lies within what the noise-free readings in that reach allow.
TEST_P(EveryPreset, RecordingReadsBackWithLabelsTruthAndDepthInAgreement) {
    const SynthPreset& preset = *findSynthPreset(GetParam());
    writeReadAndCheck(preset, /*noiseScale=*/0.f, /*interiorRadius_px=*/0);
    synth::NoiseModel noise;
    noise.scale = preset.noiseMultiplier;
    writeReadAndCheck(preset, /*noiseScale=*/1.f, lateralReach_px(noise));
}

std::vector<std::string> presetNames() {
    std::vector<std::string> names;
    for (const SynthPreset& p : synthPresets()) names.push_back(p.name);
    return names;
}

INSTANTIATE_TEST_SUITE_P(Synth, EveryPreset, ::testing::ValuesIn(presetNames()),
                         [](const auto& info) {
                             std::string n = info.param;
                             for (char& c : n)
                                 if (c == '-') c = '_';
                             return n;
                         });

}  // namespace
}  // namespace meadow::synth
