#include "meadow/synth/synthetic_tuft.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "meadow/capture/recording.h"
#include "meadow/core/atomic_file.h"
#include "meadow/synth/error.h"
#include "meadow/synth/simulated_sensor.h"
#include "meadow/synth/synthesize.h"
#include "support/truth_oracles.h"

using namespace meadow::modeling;
using namespace meadow::synth;
using meadow::test::interior;
using meadow::test::rayDepth_m;
namespace capture = meadow::capture;
namespace fs = std::filesystem;

namespace {

fs::path freshDir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("meadow_synth_" + name);
    fs::remove_all(dir);
    return dir;
}

SyntheticTuft presetFrame(const std::string& name, int frame = 0, bool scenery = true) {
    const SynthPreset* preset = findSynthPreset(name);
    if (!preset) throw std::runtime_error("no preset " + name);
    TuftSpec spec = buildPresetSpec(*preset, {});
    spec.scenery = scenery;
    return buildTuft(spec, frame);
}

}  // namespace

TEST(SyntheticTuft, EveryPresetBuildsPlausibleBladesFacingTheCamera) {
    ASSERT_GE(synthPresets().size(), 12u);
    for (const std::string name :
         {"slim-grass", "quadratic-leaf", "shrub-leaf", "bamboo-leaf", "sharp-tip", "touching",
          "asymmetric", "curl", "thin", "tilted", "noisy", "wind"}) {
        const SynthPreset* preset = findSynthPreset(name);
        ASSERT_NE(preset, nullptr) << name;
        EXPECT_FALSE(preset->description.empty());
        EXPECT_EQ(preset->description.find('\n'), std::string::npos) << name;
        const SyntheticTuft tuft = presetFrame(name);
        EXPECT_GE(tuft.blades.size(), 3u) << name;
        EXPECT_LE(tuft.blades.size(), 12u) << name;
        EXPECT_EQ(tuft.scenery.size(), 2u) << name << ": ground and wall";
        for (std::size_t i = 0; i < tuft.blades.size(); ++i) {
            const SyntheticBlade& b = tuft.blades[i];
            EXPECT_EQ(b.id, i + 1) << name;
            EXPECT_GE(b.archetype.height_m(), 0.08f) << name;
            EXPECT_LE(b.archetype.height_m(), 0.35f + 1e-4f) << name;
            EXPECT_LE(b.archetype.width.maxWidth_m(), 0.025f + 1e-6f) << name;
            const QuadraticBezier spine = b.spineInCamera_m();
            EXPECT_GT(spine.v0.z, 0.45f) << name;
            EXPECT_LT(spine.v0.z, 1.25f) << name;
            const glm::vec2 tip = preset->name == "tilted"
                                      ? glm::vec2(320, 240)
                                      : capture::Intrinsics{}.project(spine.v2);
            EXPECT_LT(tip.y, 480.f) << name << " blade " << b.id << " tip below the image";
            // The face plane faces the camera: its normal at the base is mostly along the view.
            const glm::vec3 n = glm::mat3(b.cameraFromBlade) * glm::vec3(0, 0, 1);
            if (preset->name != "tilted") {
                EXPECT_GT(std::abs(n.z), 0.8f) << name << " " << b.id;
            }
        }
    }
    EXPECT_EQ(findSynthPreset("nope"), nullptr);
    EXPECT_NE(synthPresetNames().find("wind"), std::string::npos);
}

TEST(SyntheticTuft, SpineWithLengthHitsTheLengthAndKeepsTheBaseDirection) {
    const glm::vec3 v0{0.f}, up{0.f, 1.f, 0.f}, v2{0.05f, 0.12f, 0.01f};
    const QuadraticBezier c = spineWithLength(v0, up, v2, 0.15f);
    EXPECT_NEAR(c.length(), 0.15f, 1e-6f);
    EXPECT_LT(glm::length(glm::cross(glm::normalize(c.v1 - c.v0), up)), 1e-6f);
    EXPECT_EQ(c.v2, v2);
    EXPECT_THROW((void)spineWithLength(v0, up, {0.f, 0.2f, 0.f}, 0.15f), std::invalid_argument);
}

TEST(SyntheticTuft, WindMovesTheTipsButKeepsEverySpineLength) {
    const SynthPreset* wind = findSynthPreset("wind");
    const TuftSpec spec = buildPresetSpec(*wind, {});
    const SyntheticTuft first = buildTuft(spec, 0), later = buildTuft(spec, 7);
    ASSERT_EQ(first.blades.size(), later.blades.size());
    float largestTipMove_m = 0.f;
    for (std::size_t i = 0; i < first.blades.size(); ++i) {
        const QuadraticBezier a = first.blades[i].spineInCamera_m();
        const QuadraticBezier b = later.blades[i].spineInCamera_m();
        EXPECT_NEAR(a.length(), b.length(), 1e-5f) << "blade " << i + 1;
        EXPECT_NEAR(a.length(), spec.blades[i].archetype.height_m(), 1e-5f);
        EXPECT_LT(glm::length(a.v0 - b.v0), 1e-6f) << "the base stays";
        largestTipMove_m = std::max(largestTipMove_m, glm::length(a.v2 - b.v2));
    }
    EXPECT_GT(largestTipMove_m, 0.01f) << "the gust moves some tip by more than a centimetre";
}

TEST(SyntheticTuft, LabelledPixelsCarryTheTruthMeshDepthWithinTheNoiseModel) {
    const SyntheticTuft tuft = presetFrame("quadratic-leaf");
    const meadow::synth::NoiseModel noise;  // nominal
    const meadow::synth::SimulatedSensor sensor(capture::Intrinsics::kinectV1(), noise);
    const meadow::synth::SimulatedFrame frame = sensor.render(tuft.meshes(), 42);
    const capture::Intrinsics& k = sensor.intrinsics();
    std::vector<TriangleMesh> truthMeshes;
    for (const SyntheticBlade& b : tuft.blades) truthMeshes.push_back(b.meshInCamera());

    int checked = 0, within = 0, worstU = 0, worstV = 0;
    float worstExcess_m = 0.f;
    for (int v = 0; v < k.height_px; ++v)
        for (int u = 0; u < k.width_px; ++u) {
            const int id = frame.labels(v, u);
            if (id == 0 || !interior(frame.labels, u, v, /*radius=*/2) || frame.depth_mm(v, u) == 0)
                continue;
            ASSERT_LE(id, static_cast<int>(truthMeshes.size()));
            const float exact_m = rayDepth_m(truthMeshes[id - 1], k, u, v);
            ASSERT_TRUE(std::isfinite(exact_m)) << "pixel " << u << "," << v << " labelled " << id
                                                << " but its ray misses the truth mesh";
            const float sigma_m =
                noise.scale * meadow::synth::axialSigma_m(exact_m, frame.incidence_rad(v, u));
            const float tolerance_m =
                4.f * sigma_m +
                0.5f * meadow::synth::disparityStep_m(exact_m, k.fx_px, noise.baseline_m,
                                                      noise.subpixel) +
                0.0005f;  // millimetre rounding
            const float error_m = std::abs(frame.depth_mm(v, u) * 1e-3f - exact_m);
            ++checked;
            if (error_m < tolerance_m) {
                ++within;
            } else if (error_m - tolerance_m > worstExcess_m) {
                worstExcess_m = error_m - tolerance_m;
                worstU = u;
                worstV = v;
            }
        }
    ASSERT_GT(checked, 1000) << "too few interior blade pixels to judge";
    EXPECT_GE(within, 0.99 * checked)
        << within << " of " << checked << " within 4 sigma; worst " << worstExcess_m * 1e3f
        << " mm over at " << worstU << "," << worstV;
}

TEST(SyntheticTuft, NothingRenderedReadsNothingBeyondABoundedEdgeRate) {
    const SyntheticTuft tuft = presetFrame("slim-grass", 0, /*scenery=*/false);
    const meadow::synth::SimulatedSensor sensor;
    const meadow::synth::SimulatedFrame frame = sensor.render(tuft.meshes(), 7);
    cv::Mat1b rendered = frame.exact_m > 0.f;
    cv::Mat1b near;
    // Lateral noise moves silhouettes by N(0, 0.8 px): 3 px is nearly 4 sigma.
    cv::dilate(rendered, near, cv::Mat::ones(7, 7, CV_8U));
    int nothing = 0, readings = 0, farReadings = 0;
    for (int v = 0; v < rendered.rows; ++v)
        for (int u = 0; u < rendered.cols; ++u) {
            if (rendered(v, u)) continue;
            ++nothing;
            if (frame.depth_mm(v, u) == 0) continue;
            ++readings;
            if (!near(v, u)) ++farReadings;
        }
    EXPECT_EQ(farReadings, 0) << "readings more than 3 px from anything rendered";
    EXPECT_LE(readings, 0.01 * nothing)
        << readings << " readings on " << nothing << " empty pixels";
}

TEST(Synthesize, WritesARecordingWhoseLabelIdsAreTheTruthIds) {
    const fs::path out = freshDir("labels");
    SynthOptions options;
    options.preset = "sharp-tip";
    options.out = out;
    options.frames = 2;
    std::vector<int> progress;
    const SynthTruth truth =
        synthesize(options, [&](int done, int total) { progress.push_back(done * 100 + total); });
    EXPECT_EQ(progress, (std::vector<int>{102, 202}));
    EXPECT_EQ(capture::readRecordingInfo(out).frameCount, 2);
    ASSERT_EQ(truth.frames.size(), 2u);
    for (const SynthTruthFrame& f : truth.frames) {
        const cv::Mat labels =
            cv::imread((out / "truth" / f.labels).string(), cv::IMREAD_UNCHANGED);
        ASSERT_EQ(labels.type(), CV_16UC1) << f.labels;
        std::set<int> truthIds{0}, seen;
        for (const SynthTruthBlade& b : f.blades) truthIds.insert(b.id);
        for (int v = 0; v < labels.rows; ++v)
            for (int u = 0; u < labels.cols; ++u) seen.insert(labels.at<std::uint16_t>(v, u));
        EXPECT_EQ(seen, truthIds) << "every blade visible, no other id";
    }
    EXPECT_EQ(readSynthTruth(out / "truth" / "blades.json"), truth);
    // Running again over the same folder replaces it.
    options.frames = 1;
    EXPECT_EQ(synthesize(options).frames.size(), 1u);
    EXPECT_FALSE(fs::exists(out / "truth" / "labels" / "000001.png"));
}

TEST(Synthesize, SameSeedSameTruthAndAnUnknownPresetNamesTheKnownOnes) {
    SynthOptions options;
    options.preset = "wind";
    options.out = freshDir("seed_a");
    options.frames = 2;
    const SynthTruth a = synthesize(options);
    options.out = freshDir("seed_b");
    EXPECT_EQ(synthesize(options), a);
    EXPECT_NE(a.frames[0].blades[0].spineCamera_m.v2, a.frames[1].blades[0].spineCamera_m.v2);
    options.preset = "meadow";
    try {
        (void)synthesize(options);
        FAIL() << "unknown preset accepted";
    } catch (const SynthError& e) {
        EXPECT_NE(std::string(e.what()).find("slim-grass"), std::string::npos) << e.what();
    }
}

TEST(SynthTruth, JsonRoundTripsAndRejectsOtherVersions) {
    SynthTruth t;
    t.preset = "curl";
    t.seed = 18446744073709551615ull;
    t.noiseScale = 0.5f;
    t.sensorNoiseScale = 1.5f;
    t.distance_m = 0.8f;
    t.cameraTilt_rad = 0.61086524f;
    t.cameraFromWorld[3] = glm::vec4(0.1f, -0.2f, 0.8f, 1.f);
    t.frames.push_back(truthOfFrame(presetFrame("curl"), 0));
    t.frames.front().timestamp_s = 1.0 / 30.0;
    const std::string text = synthTruthToJson(t);
    EXPECT_EQ(parseSynthTruth(text, "mem"), t);

    std::string other = text;
    other.replace(other.find("\"version\": 1"), 12, "\"version\": 9");
    try {
        (void)parseSynthTruth(other, "blades.json");
        FAIL() << "version 9 accepted";
    } catch (const SynthError& e) {
        EXPECT_NE(std::string(e.what()).find("version 9"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("blades.json"), std::string::npos) << e.what();
    }
    EXPECT_THROW((void)parseSynthTruth("{", "x"), SynthError);
    EXPECT_THROW((void)readSynthTruth("/nonexistent/blades.json"), SynthError);
}

TEST(Synthesize, RefusesAFolderHoldingSomethingElseAndLeavesItAlone) {
    const fs::path out = freshDir("foreign");
    fs::create_directories(out / "truth");
    meadow::writeFileAtomically(out / "truth" / "notes.txt", "mine");
    SynthOptions options;
    options.preset = "sharp-tip";
    options.out = out;
    options.frames = 1;
    EXPECT_THROW((void)synthesize(options), meadow::Error);
    EXPECT_TRUE(fs::exists(out / "truth" / "notes.txt"));
}
