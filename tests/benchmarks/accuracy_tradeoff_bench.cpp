// Accuracy against speed, measured against the simulated sensor's ground truth (design notes,
// "Measuring"). Synthetic tufts (modeling/synthetic_tuft.h presets, rendered in memory through
// capture::SimulatedSensor exactly as `meadow synth` does) go through the segmenter and the blade
// fit; the result is compared with the exact truth. Writes, under --out (default
// docs/measurements):
//   segmentation_accuracy.csv/.md  preset x noise: recall, precision, median IoU, flags raised
//   capture_tradeoff.csv/.md/.png  median IoU against segmentation time: fusion, sigma, plane fit
//   modeling_accuracy.csv/.md      blade-type preset x noise x distance: spine / tip / height /
//                                  width errors of the fitted archetypes
//   modeling_tradeoff.csv/.md/.png spine error against capture time per tuft: refined knots,
//                                  fusion frames, tolerance (+ _knots/_width charts)
//   fig12_<preset>.csv, fig12_all.csv, fig12.md, fig12.png  Fan & Sheng 2017 Fig. 12 on the
//                                  skeletons the fit extracted from each preset
// Charts are drawn by tools/chart.sh (gnuplot). Times are wall time (std::chrono::steady_clock),
// median over repetitions, one thread; the thread's CPU time is written beside it because the
// shared build machine is loaded. --quick: fewer presets, seeds and repetitions (smoke run).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <glm/geometric.hpp>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "meadow/capture/atomic_file.h"
#include "meadow/capture/frame_memory.h"
#include "meadow/capture/segmenter.h"
#include "meadow/capture/simulated_sensor.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/capture_pipeline.h"
#include "meadow/modeling/chain_simulation.h"
#include "meadow/modeling/error.h"
#include "meadow/modeling/hausdorff.h"
#include "meadow/modeling/skeleton_refiner.h"
#include "meadow/modeling/synthetic_tuft.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;
using capture::BladeContour;
using capture::BladeFlag;
using capture::DepthFrame;
using capture::PlaneMethod;
using capture::Segmentation;
using capture::SegmenterParams;
using modeling::BladeFit;
using modeling::CaptureOptions;
using modeling::QuadraticBezier;
using modeling::SyntheticTuft;

// ---- What is measured --------------------------------------------------------------------
constexpr double kMatchIou = 0.5;  // a found blade matches a true one at pixel IoU >= this
const std::vector<std::string> kBladeTypePresets{"slim-grass", "quadratic-leaf", "shrub-leaf",
                                                 "bamboo-leaf", "sharp-tip"};
const std::vector<float> kNoiseScales{0.f, 1.f, 2.f, 4.f};
constexpr float kNominalNoise = 1.f;
const std::vector<float> kModelingDistances_m{0.6f, 0.8f, 1.0f};
constexpr double kFrameRate_hz = 30.0;  // as `meadow synth` records
constexpr int kMaxFusionFrames = 5;
const std::vector<int> kFusionFrames{1, 2, 3, 5};
const std::vector<float> kSmoothingSigmas_px{0.f, 1.f, 2.f, 4.f, 8.f};
const std::vector<int> kRefinedKnots{0, 4, 8, 16, 32, 64};  // 0: refining off (its cost)
const std::vector<int> kModelingFusionFrames{1, 3, 5};
const std::vector<float> kTolerances_mm{0.f, 0.5f, 1.f, 2.f, 4.f, 8.f};
const std::vector<int> kFig12Knots{128, 64, 32, 16, 8};  // 128 = the full skeleton, error 0
constexpr int kFig12RandomTrials = 4;
constexpr int kMaxFig12BladesPerPreset = 8;  // each costs ~1.5 s of Hausdorff
constexpr int kTruthSpineSamples = 400;      // dense truth spine for distances
constexpr int kWidthComparisonSamples = 50;
constexpr float kMillimetresPerMetre = 1000.f;
constexpr double kPercent = 100.0;

struct Plan {
    std::vector<std::string> segmentationPresets;  // every preset of `meadow synth --list`
    std::vector<std::string> bladeTypes = kBladeTypePresets;
    std::vector<float> noises = kNoiseScales;
    std::vector<float> distances_m = kModelingDistances_m;
    int segmentationSeeds = 5;
    int modelingSeeds = 2;
    int tradeoffSeeds = 2;
    int repetitions = 5;
    bool verbose = false;  // one line per fitted blade in the modeling accuracy run
};

Plan makePlan(bool quick) {
    Plan plan;
    for (const auto& p : modeling::synthPresets()) plan.segmentationPresets.push_back(p.name);
    if (quick) {
        plan.segmentationPresets = {"quadratic-leaf", "touching", "thin"};
        plan.bladeTypes = {"quadratic-leaf", "sharp-tip"};
        plan.noises = {0.f, 1.f};
        plan.distances_m = {0.8f};
        plan.segmentationSeeds = 1;
        plan.modelingSeeds = 1;
        plan.tradeoffSeeds = 1;
        plan.repetitions = 1;
    }
    return plan;
}

// ---- Small helpers -----------------------------------------------------------------------
double threadCpu_ms() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

template <class T>
double median(std::vector<T> v) {
    if (v.empty()) return 0.0;
    const auto mid = v.begin() + static_cast<long>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    if (v.size() % 2 == 1) return static_cast<double>(*mid);
    const T upper = *mid;
    const T lower = *std::max_element(v.begin(), mid);
    return 0.5 * (static_cast<double>(lower) + static_cast<double>(upper));
}

template <class T>
double mean(const std::vector<T>& v) {
    if (v.empty()) return 0.0;
    double sum = 0.0;
    for (const T& x : v) sum += static_cast<double>(x);
    return sum / static_cast<double>(v.size());
}

std::string fixed(double value, int decimals) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(decimals) << value;
    return s.str();
}

// A CSV cell: blank when nothing was measured (gnuplot then draws no point).
template <class T>
std::string orBlank(const std::vector<T>& values, double value, int decimals) {
    return values.empty() ? std::string() : fixed(value, decimals);
}

std::string noiseName(float noise) { return fixed(noise, 0) + "x"; }

// Times `work` `repetitions` times: median wall (steady_clock) and thread CPU time in ms.
struct Timing {
    double wall_ms = 0.0, cpu_ms = 0.0;
};
Timing timeMedian(int repetitions, const std::function<void()>& work) {
    std::vector<double> wall, cpu;
    for (int r = 0; r < repetitions; ++r) {
        const double c0 = threadCpu_ms();
        const auto t0 = std::chrono::steady_clock::now();
        work();
        const auto t1 = std::chrono::steady_clock::now();
        cpu.push_back(threadCpu_ms() - c0);
        wall.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    }
    return {median(wall), median(cpu)};
}

// ---- Scenes: a preset rendered in memory, as `meadow synth` renders it --------------------
// SplitMix64 mix of (seed, frame) into a per-frame sensor seed, the same construction as
// modeling/src/synthesize.cpp, so frames of a fused group carry independent noise.
std::uint64_t frameSeed(std::uint64_t seed, std::uint64_t frame) {
    std::uint64_t z = seed + 0x9e3779b97f4a7c15ull * (frame + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

struct Scene {
    std::string preset;
    float noise = 1.f;
    std::uint64_t seed = 1;
    float distance_m = 0.f;
    std::vector<DepthFrame> frames;
    cv::Mat1w labels;    // truth of frame 0: blade id per pixel, 0 = none
    SyntheticTuft tuft;  // frame 0
};

Scene renderScene(const std::string& presetName, float noise, std::uint64_t seed, float distance_m,
                  int frameCount) {
    const modeling::SynthPreset* preset = modeling::findSynthPreset(presetName);
    if (!preset) throw std::invalid_argument("unknown preset " + presetName);
    modeling::TuftParams params;
    params.seed = seed;
    params.distance_m = distance_m;
    modeling::TuftSpec spec = modeling::buildPresetSpec(*preset, params);
    spec.wind.frameRate_hz = static_cast<float>(kFrameRate_hz);
    capture::NoiseModel model;
    model.scale = noise * preset->noiseMultiplier;
    const capture::SimulatedSensor sensor(spec.camera.intrinsics, model);
    Scene scene{presetName, noise, seed, spec.camera.distance_m, {}, {}, {}};
    for (int i = 0; i < frameCount; ++i) {
        SyntheticTuft tuft = modeling::buildTuft(spec, i);
        const capture::SimulatedFrame sim =
            sensor.render(tuft.meshes(), frameSeed(seed, static_cast<std::uint64_t>(i)));
        DepthFrame frame;
        frame.depth_mm = sim.depth_mm;
        frame.intrinsics = spec.camera.intrinsics;
        frame.index = i;
        frame.timestamp_s = i / kFrameRate_hz;
        scene.frames.push_back(std::move(frame));
        if (i == 0) {
            scene.labels = sim.labels;
            scene.tuft = std::move(tuft);
        }
    }
    return scene;
}

// ---- Matching found blades to true blades by pixel IoU -----------------------------------
struct BladeMatch {
    std::vector<int> trueIds;         // labels visible in frame 0
    std::vector<double> trueBestIou;  // per true id: IoU of its one-to-one partner (0 if none)
    std::vector<int> foundToTrueId;   // per found blade: matched true id (IoU >= kMatchIou), or 0
    int matched = 0;
};

// Greedy one-to-one matching by IoU over every (true, found) pair, highest IoU first (the same
// rule as tests/modeling/segmentation_accuracy_test.cpp).
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

// ---- Capture of one tuft: segmentation + fit of every trustworthy blade -------------------
// Mirrors modeling::captureArchetypes (capture_pipeline.cpp) for one fused group, keeping what
// the library drops (the blade masks and camera-space spines) to compare with the truth.
// Flags that make capture skip a blade (capture_pipeline.cpp, disqualifies()).
bool disqualifies(BladeFlag flag) { return flag != BladeFlag::Asymmetric; }

struct TuftCapture {
    Segmentation segmentation;
    std::vector<std::optional<BladeFit>> fits;  // per found blade; empty when skipped or failed
    int fitFailures = 0;
};

TuftCapture captureTuft(const capture::Segmenter& segmenter, const Scene& scene,
                        const CaptureOptions& options) {
    TuftCapture out;
    out.segmentation = segmentScene(segmenter, scene, options.fusionFrames);
    const DepthFrame& depthFrame = scene.frames.front();  // capture fits on the group's first
    for (std::size_t index = 0; index < out.segmentation.blades.size(); ++index) {
        const BladeContour& blade = out.segmentation.blades[index];
        const bool flagged = std::any_of(blade.flags.begin(), blade.flags.end(), disqualifies);
        if (flagged && !options.keepFlagged) {
            out.fits.emplace_back();
            continue;
        }
        try {
            // Rooted at the cluster's base point, as `meadow capture` fits.
            out.fits.emplace_back(
                modeling::fitSegmentedBlade(out.segmentation, index, depthFrame, options.fit));
        } catch (const modeling::ModelingError&) {
            out.fits.emplace_back();
            ++out.fitFailures;
        }
    }
    return out;
}

// ---- Errors of one fitted blade against its true blade -----------------------------------
struct BladeError {
    float v0_mm = 0.f, v1_mm = 0.f, v2_mm = 0.f;  // control points, camera space
    float heightError = 0.f;                      // (fitted - true) / true, signed
    float widthMaeFraction = 0.f;                 // mean |w_fit(s) - w_true(s)| / max true width
    float offCurve_mm = 0.f;  // largest distance of the fitted spine from the true spine curve
    // Largest distance of the refined-knot polyline from it; NaN when refining was off.
    float knotPolyline_mm = std::numeric_limits<float>::quiet_NaN();
    float baseS = 0.f, tipS = 0.f;  // arc fraction of the true spine nearest the fitted v0 / v2
    [[nodiscard]] float controlPointMean_mm() const { return (v0_mm + v1_mm + v2_mm) / 3.f; }
};

BladeError bladeError(const BladeFit& fit, const modeling::SyntheticBlade& truth) {
    const QuadraticBezier spine = truth.spineInCamera_m();
    const float trueHeight_m = spine.length();
    std::vector<glm::vec3> dense(kTruthSpineSamples + 1);
    std::vector<float> denseS(kTruthSpineSamples + 1);
    for (int i = 0; i <= kTruthSpineSamples; ++i) {
        const float t = static_cast<float>(i) / kTruthSpineSamples;
        dense[static_cast<std::size_t>(i)] = spine.at(t);
        denseS[static_cast<std::size_t>(i)] = spine.lengthTo(t) / trueHeight_m;
    }
    const auto nearest = [&](const glm::vec3& p) {  // (arc fraction, distance m)
        float bestD = std::numeric_limits<float>::max(), bestS = 0.f;
        for (std::size_t i = 0; i < dense.size(); ++i)
            if (const float d = glm::distance(p, dense[i]); d < bestD) bestD = d, bestS = denseS[i];
        return std::pair<float, float>{bestS, bestD};
    };
    BladeError e;
    const QuadraticBezier& f = fit.spineCamera_m;
    e.v0_mm = glm::distance(f.v0, spine.v0) * kMillimetresPerMetre;
    e.v1_mm = glm::distance(f.v1, spine.v1) * kMillimetresPerMetre;
    e.v2_mm = glm::distance(f.v2, spine.v2) * kMillimetresPerMetre;
    e.heightError = (fit.archetype.height_m() - trueHeight_m) / trueHeight_m;
    double widthSum_m = 0.0;
    for (int i = 0; i <= kWidthComparisonSamples; ++i) {
        const float s = static_cast<float>(i) / kWidthComparisonSamples;
        widthSum_m += std::abs(fit.archetype.width.at(s) - truth.archetype.width.at(s));
    }
    e.widthMaeFraction = static_cast<float>(widthSum_m / (kWidthComparisonSamples + 1) /
                                            truth.archetype.width.maxWidth_m());
    for (int i = 0; i <= kWidthComparisonSamples; ++i)
        e.offCurve_mm = std::max(
            e.offCurve_mm, nearest(f.at(static_cast<float>(i) / kWidthComparisonSamples)).second *
                               kMillimetresPerMetre);
    if (fit.archetype.knots_m.size() >= 2) {
        std::vector<glm::vec3> knots;
        for (const glm::vec3& k : fit.archetype.knots_m) knots.push_back(fit.frame.toCamera(k));
        e.knotPolyline_mm = modeling::directedHausdorff_m(knots, dense) * kMillimetresPerMetre;
    }
    e.baseS = nearest(f.v0).first;
    e.tipS = nearest(f.v2).first;
    return e;
}

struct FittedRecord {
    std::string preset;
    float noise = 0.f, distance_m = 0.f;
    BladeError error;
};

// Fitted blades matched one-to-one to true blades by label IoU (>= kMatchIou); the rest counted.
struct TuftScore {
    int trueBlades = 0;       // visible true blades
    int found = 0;            // blades the segmenter returned
    int fitted = 0;           // archetypes the capture produced
    int fittedMatched = 0;    // ... of which match a true blade
    int fitFailures = 0;      // fitBlade threw
    std::vector<double> iou;  // per visible true blade
    std::vector<BladeError> errors;
    std::vector<const BladeFit*> matchedFits;  // parallel to errors (valid while capture lives)
};

TuftScore scoreCapture(const Scene& scene, const TuftCapture& cap) {
    TuftScore s;
    const BladeMatch m = matchBlades(scene.labels, cap.segmentation.blades);
    s.trueBlades = static_cast<int>(m.trueIds.size());
    s.found = static_cast<int>(cap.segmentation.blades.size());
    s.fitFailures = cap.fitFailures;
    s.iou = m.trueBestIou;
    for (std::size_t b = 0; b < cap.fits.size(); ++b) {
        if (!cap.fits[b]) continue;
        ++s.fitted;
        const int id = m.foundToTrueId[b];
        if (id == 0) continue;
        ++s.fittedMatched;
        s.errors.push_back(
            bladeError(*cap.fits[b], scene.tuft.blades.at(static_cast<std::size_t>(id - 1))));
        s.matchedFits.push_back(&*cap.fits[b]);
    }
    return s;
}

// ---- Output ------------------------------------------------------------------------------
void writeText(const fs::path& path, const std::string& text) {
    writeFileAtomically(path, text);
    std::cout << "  wrote " << path.string() << '\n';
}

void chart(const fs::path& csv, const fs::path& png, const std::string& title, const std::string& x,
           const std::string& y, const std::string& series, const std::string& xLabel,
           const std::string& yLabel, const std::string& scale = "") {
    const fs::path script = fs::path(MEADOW_SOURCE_DIR) / "tools" / "chart.sh";
    const auto quote = [](const std::string& s) {  // one shell word, quotes in it escaped
        std::string q = "'";
        for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
        return q + "'";
    };
    const std::string command = quote(script.string()) + ' ' + quote(csv.string()) + ' ' +
                                quote(png.string()) + ' ' + quote(title) + ' ' + x + ' ' + y + ' ' +
                                series + ' ' + quote(xLabel) + ' ' + quote(yLabel) + ' ' + scale;
    if (std::system(command.c_str()) != 0)
        std::cerr << "  chart.sh failed for " << png.string() << " (is gnuplot installed?)\n";
    else
        std::cout << "  wrote " << png.string() << '\n';
}

// "overlapping x2, too-thin x1, no blades x3" (frames with an empty result), or "-".
std::string flagCounts(const std::map<std::string, int>& counts, int emptyFrames) {
    std::string text;
    for (const auto& [name, n] : counts)
        text += (text.empty() ? "" : ", ") + name + " x" + std::to_string(n);
    if (emptyFrames > 0)
        text +=
            (text.empty() ? "" : ", ") + std::string("no blades x") + std::to_string(emptyFrames);
    return text.empty() ? "-" : text;
}

// Trade-off CSV rows: chart.sh joins a series' points in file order, so within each knob the
// rows are written by increasing time (the knob's values are in the CSV's value column).
struct TradeoffRow {
    std::string knob;
    double time_ms = 0.0;
    std::string line;
};
std::string sortedRows(std::vector<TradeoffRow> rows) {
    std::vector<std::string> knobOrder;
    for (const TradeoffRow& r : rows)
        if (std::find(knobOrder.begin(), knobOrder.end(), r.knob) == knobOrder.end())
            knobOrder.push_back(r.knob);
    const auto rank = [&](const std::string& knob) {
        return std::find(knobOrder.begin(), knobOrder.end(), knob) - knobOrder.begin();
    };
    std::stable_sort(rows.begin(), rows.end(), [&](const TradeoffRow& a, const TradeoffRow& b) {
        return rank(a.knob) != rank(b.knob) ? rank(a.knob) < rank(b.knob) : a.time_ms < b.time_ms;
    });
    std::string text;
    for (const TradeoffRow& r : rows) text += r.line;
    return text;
}

// ---- 1. Segmentation accuracy: preset x noise ---------------------------------------------
const std::vector<BladeFlag> kAllFlags{BladeFlag::Overlapping, BladeFlag::CurlsSideways,
                                       BladeFlag::TooThin,     BladeFlag::BaseHidden,
                                       BladeFlag::Asymmetric,  BladeFlag::Truncated};

void segmentationAccuracy(const Plan& plan, const fs::path& out) {
    std::cout << "segmentation accuracy: " << plan.segmentationPresets.size() << " presets x "
              << plan.noises.size() << " noise scales x " << plan.segmentationSeeds << " seeds\n";
    std::ostringstream csv, md;
    csv << "preset,noise_scale,seeds,true_blades,found_blades,recall,precision,median_iou,"
           "flagged_blades,unflagged_unmatched";
    for (BladeFlag f : kAllFlags) csv << ",flag_" << capture::toString(f);
    csv << ",cluster_flags,empty_frames,zero_recall_frames\n";
    md << "| preset | noise | true / found (per frame) | recall | precision | median IoU | "
          "frames with no blade matched | flags raised (blades, "
       << plan.segmentationSeeds
       << " frames) | unmatched and unflagged |\n|---|---|---|---|---|---|---|---|---|\n";
    const capture::Segmenter segmenter;
    for (const std::string& preset : plan.segmentationPresets)
        for (float noise : plan.noises) {
            std::vector<double> recall, precision, medianIou;
            double trueSum = 0.0, foundSum = 0.0;
            int flagged = 0, silentWrong = 0, clusterFlags = 0, empty = 0, zeroRecall = 0;
            std::map<std::string, int> flagKinds;
            std::map<BladeFlag, int> perFlag;
            for (int seed = 1; seed <= plan.segmentationSeeds; ++seed) {
                const Scene scene =
                    renderScene(preset, noise, static_cast<std::uint64_t>(seed), 0.f, 1);
                const Segmentation seg = segmenter.segment(scene.frames.front());
                const BladeMatch m = matchBlades(scene.labels, seg.blades);
                const auto nTrue = static_cast<double>(m.trueIds.size());
                const auto nFound = static_cast<double>(seg.blades.size());
                trueSum += nTrue;
                foundSum += nFound;
                recall.push_back(nTrue > 0 ? m.matched / nTrue : 1.0);
                if (nFound > 0) precision.push_back(m.matched / nFound);  // else undefined
                medianIou.push_back(median(m.trueBestIou));
                if (seg.empty()) ++empty;
                if (m.matched == 0 && nTrue > 0) ++zeroRecall;
                for (std::size_t b = 0; b < seg.blades.size(); ++b) {
                    const BladeContour& blade = seg.blades[b];
                    if (!blade.flags.empty()) ++flagged;
                    if (blade.flags.empty() && m.foundToTrueId[b] == 0) ++silentWrong;
                    for (BladeFlag f : blade.flags) {
                        ++perFlag[f];
                        ++flagKinds[capture::toString(f)];
                    }
                }
                for (const auto& c : seg.clusters) {
                    clusterFlags += static_cast<int>(c.flags.size());
                    for (BladeFlag f : c.flags) ++flagKinds["cluster " + capture::toString(f)];
                }
            }
            const double seeds = plan.segmentationSeeds;
            csv << preset << ',' << noise << ',' << plan.segmentationSeeds << ','
                << fixed(trueSum / seeds, 2) << ',' << fixed(foundSum / seeds, 2) << ','
                << fixed(mean(recall), 3) << ','
                << (precision.empty() ? std::string() : fixed(mean(precision), 3)) << ','
                << fixed(mean(medianIou), 3) << ',' << flagged << ',' << silentWrong;
            for (BladeFlag f : kAllFlags) csv << ',' << perFlag[f];
            csv << ',' << clusterFlags << ',' << empty << ',' << zeroRecall << '\n';
            md << "| " << preset << " | " << noiseName(noise) << " | " << fixed(trueSum / seeds, 1)
               << " / " << fixed(foundSum / seeds, 1) << " | " << fixed(mean(recall), 2) << " | "
               << (precision.empty() ? std::string("–") : fixed(mean(precision), 2)) << " | "
               << fixed(mean(medianIou), 2) << " | " << zeroRecall << " | "
               << flagCounts(flagKinds, empty) << " | " << silentWrong << " |\n";
            std::cout << "  " << preset << ' ' << noiseName(noise) << ": recall "
                      << fixed(mean(recall), 2) << ", median IoU " << fixed(mean(medianIou), 2)
                      << '\n';
        }
    writeText(out / "segmentation_accuracy.csv", csv.str());
    writeText(out / "segmentation_accuracy.md", md.str());
}

// ---- 2. Capture trade-off: median IoU against segmentation time --------------------------
std::vector<Scene> tradeoffScenes(const Plan& plan) {
    std::vector<Scene> scenes;
    for (const std::string& preset : plan.bladeTypes)
        for (int seed = 1; seed <= plan.tradeoffSeeds; ++seed)
            scenes.push_back(renderScene(preset, kNominalNoise, static_cast<std::uint64_t>(seed),
                                         0.f, kMaxFusionFrames));
    return scenes;
}

void captureTradeoff(const Plan& plan, const std::vector<Scene>& scenes, const fs::path& out) {
    std::cout << "capture trade-off on " << scenes.size() << " scenes, " << plan.repetitions
              << " repetitions\n";
    struct Config {
        std::string knob, value;
        SegmenterParams params;
        int fusion;
    };
    const CaptureOptions defaults{};
    std::vector<Config> configs;
    for (int f : kFusionFrames)
        configs.push_back({"fusion-frames", std::to_string(f), defaults.segmenter, f});
    for (float sigma : kSmoothingSigmas_px) {
        SegmenterParams p = defaults.segmenter;
        p.smoothingSigma_px = sigma;
        configs.push_back({"contour-sigma-px", fixed(sigma, 1), p, defaults.fusionFrames});
    }
    for (PlaneMethod m :
         {PlaneMethod::None, PlaneMethod::Ransac, PlaneMethod::OrganizedMultiPlane}) {
        SegmenterParams p = defaults.segmenter;
        p.planeMethod = m;
        configs.push_back({"plane-fit", capture::toString(m), p, defaults.fusionFrames});
    }
    std::ostringstream csv, md;
    csv << "knob,value,time_ms,cpu_ms,median_iou,recall,precision\n";
    md << "| knob | value | time per segmentation (ms, wall) | CPU (ms) | median IoU | recall | "
          "precision |\n|---|---|---|---|---|---|---|\n";
    std::vector<TradeoffRow> rows;
    for (const Config& c : configs) {
        const capture::Segmenter segmenter(c.params);
        std::vector<double> iou, wall, cpu;
        int truth = 0, found = 0, matched = 0;
        for (const Scene& scene : scenes) {
            Segmentation seg;
            const Timing t = timeMedian(plan.repetitions,
                                        [&] { seg = segmentScene(segmenter, scene, c.fusion); });
            wall.push_back(t.wall_ms);
            cpu.push_back(t.cpu_ms);
            const BladeMatch m = matchBlades(scene.labels, seg.blades);
            iou.insert(iou.end(), m.trueBestIou.begin(), m.trueBestIou.end());
            truth += static_cast<int>(m.trueIds.size());
            found += static_cast<int>(seg.blades.size());
            matched += m.matched;
        }
        const double recall = truth ? static_cast<double>(matched) / truth : 1.0;
        const double precision = found ? static_cast<double>(matched) / found : 1.0;
        rows.push_back({c.knob, mean(cpu),
                        c.knob + ',' + c.value + ',' + fixed(mean(wall), 2) + ',' +
                            fixed(mean(cpu), 2) + ',' + fixed(median(iou), 4) + ',' +
                            fixed(recall, 3) + ',' + fixed(precision, 3) + '\n'});
        md << "| " << c.knob << " | " << c.value << " | " << fixed(mean(wall), 1) << " | "
           << fixed(mean(cpu), 1) << " | " << fixed(median(iou), 3) << " | " << fixed(recall, 2)
           << " | " << fixed(precision, 2) << " |\n";
        std::cout << "  " << c.knob << '=' << c.value << ": " << fixed(mean(wall), 1)
                  << " ms wall, " << fixed(mean(cpu), 1) << " ms CPU, median IoU "
                  << fixed(median(iou), 3) << '\n';
    }
    csv << sortedRows(rows);
    writeText(out / "capture_tradeoff.csv", csv.str());
    writeText(out / "capture_tradeoff.md", md.str());
    chart(out / "capture_tradeoff.csv", out / "capture_tradeoff.png",
          "Segmentation: median blade IoU vs time (blade-type presets, nominal noise)", "cpu_ms",
          "median_iou", "knob", "CPU time per segmentation (ms, one thread; wall time in the CSV)",
          "median blade IoU (pixels, vs truth)");
}

// ---- 3. Modeling accuracy: blade type x noise x distance ---------------------------------
struct Fig12Input {
    std::map<std::string, std::vector<std::vector<glm::vec3>>> restKnots;  // per preset
};

void appendFig12Skeleton(Fig12Input& input, const std::string& preset, const BladeFit& fit) {
    auto& blades = input.restKnots[preset];
    if (static_cast<int>(blades.size()) >= kMaxFig12BladesPerPreset) return;
    std::vector<glm::vec3> local;
    for (const glm::vec3& p : fit.skeleton.points_m) local.push_back(fit.frame.toLocal(p));
    if (local.size() >= 3) blades.push_back(std::move(local));
}

std::string modelingRow(const std::vector<BladeError>& e) {
    std::vector<float> v0, v1, v2, tipSq, heightAbs, heightSigned, width, off, knots, base, tip;
    for (const BladeError& b : e) {
        v0.push_back(b.v0_mm);
        v1.push_back(b.v1_mm);
        v2.push_back(b.v2_mm);
        tipSq.push_back(b.v2_mm * b.v2_mm);
        heightAbs.push_back(std::abs(b.heightError));
        heightSigned.push_back(b.heightError);
        width.push_back(b.widthMaeFraction);
        off.push_back(b.offCurve_mm);
        if (std::isfinite(b.knotPolyline_mm)) knots.push_back(b.knotPolyline_mm);
        base.push_back(b.baseS);
        tip.push_back(b.tipS);
    }
    std::ostringstream row;
    if (e.empty()) return ",,,,,,,,,,,";  // no fitted blade matched: nothing measured
    row << fixed(mean(v0), 2) << ',' << fixed(mean(v1), 2) << ',' << fixed(mean(v2), 2) << ','
        << fixed(std::sqrt(mean(tipSq)), 2) << ',' << fixed(kPercent * mean(heightAbs), 2) << ','
        << fixed(kPercent * mean(heightSigned), 2) << ',' << fixed(kPercent * mean(width), 2) << ','
        << fixed(median(off), 2) << ',' << fixed(mean(knots), 2) << ',' << fixed(median(base), 3)
        << ',' << fixed(median(tip), 3) << ',' << fixed(median(v2), 2);
    return row.str();
}

void modelingAccuracy(const Plan& plan, const fs::path& out, Fig12Input& fig12) {
    std::cout << "modeling accuracy: " << plan.bladeTypes.size() << " presets x "
              << plan.noises.size() << " noise x " << plan.distances_m.size() << " distances x "
              << plan.modelingSeeds << " seeds (capture defaults: fuse "
              << CaptureOptions{}.fusionFrames << " frames)\n";
    const CaptureOptions options{};
    const capture::Segmenter segmenter(options.segmenter);
    const std::string header =
        "v0_error_mm,v1_error_mm,v2_error_mm,tip_rms_mm,height_error_abs_pct,"
        "height_error_signed_pct,width_mae_pct_of_max,spine_off_curve_median_mm,"
        "knot_polyline_error_mm,base_s_median,tip_s_median,tip_error_median_mm";
    std::ostringstream csv, md;
    csv << "preset,noise_scale,distance_m,seeds,true_blades,fitted,fitted_matched,"
           "fitted_unmatched,fit_failures,"
        << header << '\n';
    md << "| preset | noise | fitted (matched) / true | v0 / v1 / v2 error (mm, mean) | tip RMS "
          "(median) (mm) | "
          "height error (mean abs, signed) | width MAE (% of max) | fitted spine off true "
          "curve (median, mm) | visible s (base-tip) |\n|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string& preset : plan.bladeTypes)
        for (float noise : plan.noises) {
            std::vector<BladeError> pooled;
            int pooledTrue = 0, pooledFitted = 0, pooledMatched = 0;
            for (float distance_m : plan.distances_m) {
                std::vector<BladeError> errors;
                int trueBlades = 0, fitted = 0, matched = 0, failures = 0;
                for (int seed = 1; seed <= plan.modelingSeeds; ++seed) {
                    const Scene scene = renderScene(preset, noise, static_cast<std::uint64_t>(seed),
                                                    distance_m, options.fusionFrames);
                    const TuftCapture cap = captureTuft(segmenter, scene, options);
                    const TuftScore s = scoreCapture(scene, cap);
                    trueBlades += static_cast<int>(scene.tuft.blades.size());
                    fitted += s.fitted;
                    matched += s.fittedMatched;
                    failures += s.fitFailures;
                    errors.insert(errors.end(), s.errors.begin(), s.errors.end());
                    if (plan.verbose)
                        for (const BladeError& e : s.errors)
                            std::cout
                                << "    " << preset << ' ' << noiseName(noise) << ' ' << distance_m
                                << " m seed " << seed << ": v0/v1/v2 " << fixed(e.v0_mm, 1) << '/'
                                << fixed(e.v1_mm, 1) << '/' << fixed(e.v2_mm, 1) << " mm, height "
                                << fixed(kPercent * e.heightError, 1) << " %, s "
                                << fixed(e.baseS, 2) << "-" << fixed(e.tipS, 2) << ", off curve "
                                << fixed(e.offCurve_mm, 1) << " mm, knots "
                                << fixed(e.knotPolyline_mm, 1) << " mm\n";
                    if (noise == kNominalNoise)
                        for (const BladeFit* f : s.matchedFits)
                            appendFig12Skeleton(fig12, preset, *f);
                }
                csv << preset << ',' << noise << ',' << distance_m << ',' << plan.modelingSeeds
                    << ',' << trueBlades << ',' << fitted << ',' << matched << ','
                    << fitted - matched << ',' << failures << ',' << modelingRow(errors) << '\n';
                pooled.insert(pooled.end(), errors.begin(), errors.end());
                pooledTrue += trueBlades;
                pooledFitted += fitted;
                pooledMatched += matched;
            }
            std::istringstream row(modelingRow(pooled));
            std::vector<std::string> f;
            for (std::string cell; std::getline(row, cell, ',');)
                f.push_back(cell.empty() ? "–" : cell);
            f.resize(12, "–");
            md << "| " << preset << " | " << noiseName(noise) << " | " << pooledFitted << " ("
               << pooledMatched << ") / " << pooledTrue << " | " << f[0] << " / " << f[1] << " / "
               << f[2] << " | " << f[3] << " (" << f[11] << ") | " << f[4] << " %, " << f[5]
               << " % | " << f[6] << " % | " << f[7] << " | "
               << (pooled.empty() ? std::string("–") : f[9] + "-" + f[10]) << " |\n";
            std::cout << "  " << preset << ' ' << noiseName(noise) << ": " << pooledMatched << '/'
                      << pooledTrue << " fitted, v0/v1/v2 " << f[0] << '/' << f[1] << '/' << f[2]
                      << " mm, height " << f[4] << " %, width " << f[6] << " %\n";
        }
    writeText(out / "modeling_accuracy.csv", csv.str());
    writeText(out / "modeling_accuracy.md", md.str());
}

// ---- 4. Modeling trade-off: spine error against capture time per tuft --------------------
// The charts put thread CPU time on x: on the shared, loaded build machine the wall time of the
// same work varied up to 2.6x between configurations (both are in the CSV).
const std::string kCpuTuftLabel =
    "CPU time per tuft: segmentation + fits (ms, one thread; wall time in the CSV)";
void modelingTradeoff(const Plan& plan, const std::vector<Scene>& scenes, const fs::path& out) {
    std::cout << "modeling trade-off on " << scenes.size() << " scenes, " << plan.repetitions
              << " repetitions\n";
    struct Config {
        std::string knob, value;
        CaptureOptions options;
    };
    std::vector<Config> configs;
    for (int k : kRefinedKnots) {
        CaptureOptions o;
        o.fit.refinedKnots = k;
        configs.push_back({"refined-knots", std::to_string(k), o});
    }
    for (int f : kModelingFusionFrames) {
        CaptureOptions o;
        o.fusionFrames = f;
        configs.push_back({"fusion-frames", std::to_string(f), o});
    }
    for (float tol : kTolerances_mm) {  // as `meadow capture --tolerance-mm`: widths and knots
        CaptureOptions o;
        o.fit.setTolerance_m(tol / kMillimetresPerMetre);
        configs.push_back({"tolerance-mm", fixed(tol, 1), o});
    }
    std::ostringstream csv, md;
    csv << "knob,value,time_ms,cpu_ms,spine_error_mm,spine_error_median_mm,"
           "spine_off_curve_median_mm,knot_polyline_error_mm,knot_polyline_median_mm,"
           "width_mae_pct_of_max,width_samples_mean,fitted_matched,knots_kept_mean\n";
    md << "| knob | value | capture time per tuft (ms, wall) | CPU (ms) | spine control-point "
          "error (mm, median / mean) | refined-knot polyline off truth (mm, median / mean) | "
          "width MAE (% of max) | width samples | knots kept | blades "
          "|\n|---|---|---|---|---|---|---|---|---|---|\n";
    std::vector<TradeoffRow> rows;
    for (const Config& c : configs) {
        const capture::Segmenter segmenter(c.options.segmenter);
        std::vector<double> wall, cpu;
        std::vector<float> cp, off, knots, width, samples, kept;
        for (const Scene& scene : scenes) {
            TuftCapture cap;
            const Timing t = timeMedian(plan.repetitions,
                                        [&] { cap = captureTuft(segmenter, scene, c.options); });
            wall.push_back(t.wall_ms);
            cpu.push_back(t.cpu_ms);
            const TuftScore s = scoreCapture(scene, cap);
            for (std::size_t i = 0; i < s.errors.size(); ++i) {
                cp.push_back(s.errors[i].controlPointMean_mm());
                off.push_back(s.errors[i].offCurve_mm);
                if (std::isfinite(s.errors[i].knotPolyline_mm))
                    knots.push_back(s.errors[i].knotPolyline_mm);
                width.push_back(s.errors[i].widthMaeFraction);
                samples.push_back(
                    static_cast<float>(s.matchedFits[i]->archetype.width.width_m.size()));
                kept.push_back(static_cast<float>(s.matchedFits[i]->archetype.knots_m.size()));
            }
        }
        rows.push_back(
            {c.knob, mean(cpu),
             c.knob + ',' + c.value + ',' + fixed(mean(wall), 2) + ',' + fixed(mean(cpu), 2) + ',' +
                 fixed(mean(cp), 3) + ',' + fixed(median(cp), 3) + ',' + fixed(median(off), 3) +
                 ',' + orBlank(knots, mean(knots), 3) + ',' + orBlank(knots, median(knots), 3) +
                 ',' + fixed(kPercent * mean(width), 2) + ',' + fixed(mean(samples), 1) + ',' +
                 std::to_string(cp.size()) + ',' + fixed(mean(kept), 1) + '\n'});
        md << "| " << c.knob << " | " << c.value << " | " << fixed(mean(wall), 1) << " | "
           << fixed(mean(cpu), 1) << " | " << fixed(median(cp), 2) << " / " << fixed(mean(cp), 2)
           << " | "
           << (knots.empty() ? std::string("– (refining off)")
                             : fixed(median(knots), 2) + " / " + fixed(mean(knots), 2))
           << " | " << fixed(kPercent * mean(width), 1) << " | " << fixed(mean(samples), 1) << " | "
           << fixed(mean(kept), 1) << " | " << cp.size() << " |\n";
        std::cout << "  " << c.knob << '=' << c.value << ": " << fixed(mean(wall), 1)
                  << " ms wall, " << fixed(mean(cpu), 1) << " ms CPU, spine " << fixed(mean(cp), 2)
                  << " mm, knots " << fixed(mean(knots), 2) << " mm, width "
                  << fixed(kPercent * mean(width), 1) << " %\n";
    }
    csv << sortedRows(rows);
    writeText(out / "modeling_tradeoff.csv", csv.str());
    writeText(out / "modeling_tradeoff.md", md.str());
    chart(out / "modeling_tradeoff.csv", out / "modeling_tradeoff.png",
          "Capture: fitted spine control-point error vs time per tuft (5 blade-type tufts)",
          "cpu_ms", "spine_error_median_mm", "knob", kCpuTuftLabel,
          "spine control-point error (mm, median over blades)");
    chart(out / "modeling_tradeoff.csv", out / "modeling_tradeoff_knots.png",
          "Capture: refined-knot polyline error vs time per tuft", "cpu_ms",
          "knot_polyline_median_mm", "knob", kCpuTuftLabel,
          "refined-knot polyline off the true spine (mm, median)");
    chart(out / "modeling_tradeoff.csv", out / "modeling_tradeoff_width.png",
          "Capture: width-profile error vs time per tuft", "cpu_ms", "width_mae_pct_of_max", "knob",
          kCpuTuftLabel, "width-profile MAE (% of the blade's max width)");
}

// ---- 5. Fan & Sheng 2017 Fig. 12 on the captured skeletons -------------------------------
// Refiner names as chart series: gnuplot would read '_' as a subscript in the key.
std::string seriesName(modeling::RefinerKind kind) {
    std::string name = modeling::toString(kind);
    std::replace(name.begin(), name.end(), '_', '-');
    return name;
}

void fig12(const Fig12Input& input, const fs::path& out) {
    std::cout << "Fig. 12 (refiners)\n";
    using modeling::RefinerKind;
    modeling::ChainSimulationParams sim;  // as blade_fit.cpp: blade-local +Y up, gravity -Y
    sim.up = {0.f, 1.f, 0.f};
    sim.gravity_mps2 = {0.f, -9.81f, 0.f};
    // Pooled over presets: compareRefiners averages uniformly over blades, so the blade-weighted
    // mean of the per-preset rows is the pooled row (without running every blade twice).
    std::map<std::pair<int, RefinerKind>, modeling::RefinerComparisonRow> pooled;
    std::size_t pooledBlades = 0;
    std::ostringstream md;
    md << "| preset | blades | knots | movement similarity | random | mean | geometry only |\n"
          "|---|---|---|---|---|---|---|\n";
    const auto mdRows = [&](const std::string& label, std::size_t blades,
                            const std::vector<modeling::RefinerComparisonRow>& rows,
                            float modeling::RefinerComparisonRow::*metric) {
        for (int k : kFig12Knots) {
            if (k == kFig12Knots.front()) continue;  // nothing culled: 0 for every refiner
            std::map<RefinerKind, float> at;
            for (const auto& r : rows)
                if (r.knots == k) at[r.refiner] = r.*metric;
            md << "| " << label << " | " << blades << " | " << k << " | "
               << fixed(at[RefinerKind::MovementSimilarity], 2) << " | "
               << fixed(at[RefinerKind::Random], 2) << " | " << fixed(at[RefinerKind::Mean], 2)
               << " | " << fixed(at[RefinerKind::GeometryOnly], 2) << " |\n";
        }
    };
    std::uint64_t seed = 1;
    for (const auto& [preset, rest] : input.restKnots) {
        if (rest.empty()) continue;
        std::vector<modeling::KnotTrajectories> frames;
        for (const auto& knots : rest) {
            sim.seed = seed++;
            frames.push_back(modeling::simulateChain(knots, sim));
        }
        const auto rows =
            modeling::compareRefiners(rest, frames, kFig12Knots, {}, kFig12RandomTrials);
        const fs::path csv = out / ("fig12_" + preset + ".csv");
        modeling::writeRefinerComparisonCsv(csv, rows);
        std::cout << "  wrote " << csv.string() << " (" << rest.size() << " blades)\n";
        mdRows(preset, rest.size(), rows, &modeling::RefinerComparisonRow::refinedHausdorff_mm);
        for (const auto& r : rows) {
            auto& p = pooled[{r.knots, r.refiner}];
            p.knots = r.knots;
            p.refiner = r.refiner;
            const auto w = static_cast<float>(rest.size());
            p.refinedHausdorff_mm += w * r.refinedHausdorff_mm;
            p.hausdorff_mm += w * r.hausdorff_mm;
            p.maxDeviation_mm += w * r.maxDeviation_mm;
        }
        pooledBlades += rest.size();
    }
    if (pooledBlades == 0) {
        std::cerr << "  no fitted skeletons: Fig. 12 skipped\n";
        return;
    }
    std::vector<modeling::RefinerComparisonRow> rows;
    for (auto& [key, r] : pooled) {
        const auto w = static_cast<float>(pooledBlades);
        r.refinedHausdorff_mm /= w;
        r.hausdorff_mm /= w;
        r.maxDeviation_mm /= w;
        rows.push_back(r);
    }
    // Per refiner, knots ascending: the order chart.sh joins the points in.
    std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
        return a.refiner != b.refiner ? a.refiner < b.refiner : a.knots < b.knots;
    });
    std::ostringstream csv;
    csv << "knots,refiner,refined_hausdorff_mm,hausdorff_mm,max_deviation_mm\n";
    for (const auto& r : rows)
        csv << r.knots << ',' << seriesName(r.refiner) << ',' << fixed(r.refinedHausdorff_mm, 4)
            << ',' << fixed(r.hausdorff_mm, 4) << ',' << fixed(r.maxDeviation_mm, 4) << '\n';
    writeText(out / "fig12_all.csv", csv.str());
    mdRows("all, refined Hausdorff", pooledBlades, rows,
           &modeling::RefinerComparisonRow::refinedHausdorff_mm);
    mdRows("all, polyline Hausdorff", pooledBlades, rows,
           &modeling::RefinerComparisonRow::hausdorff_mm);
    writeText(out / "fig12.md", md.str());
    chart(out / "fig12_all.csv", out / "fig12.png",
          "Fan and Sheng Fig. 12 on captured skeletons (" + std::to_string(pooledBlades) +
              " blades, 128 knots refined)",
          "knots", "refined_hausdorff_mm", "refiner", "knots kept (of 128, log scale)",
          "refined Hausdorff error (mm, mean over frames and blades)", "logx");
}

int run(int argc, char** argv) {
    fs::path out = "docs/measurements";
    bool quick = false, verbose = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick") {
            quick = true;
        } else if (arg == "--verbose") {
            verbose = true;
        } else if (arg == "--out" && i + 1 < argc) {
            out = argv[++i];
        } else {
            std::cerr << "usage: " << argv[0] << " [--out DIR] [--quick] [--verbose]\n"
                      << "  --out DIR  where the CSV, MD and PNG files go (default "
                         "docs/measurements)\n"
                      << "  --quick    fewer presets, seeds and repetitions: a smoke run\n"
                      << "  --verbose  one line per fitted blade (modeling accuracy)\n";
            return 2;
        }
    }
    std::cout << std::unitbuf;  // progress lines as they happen, also into a log file
    cv::setNumThreads(0);       // one thread: OpenCV's parallel_for_ runs inline
    fs::create_directories(out);
    Plan plan = makePlan(quick);
    plan.verbose = verbose;
    const auto start = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
        return fixed(
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                   0) +
               " s";
    };
    segmentationAccuracy(plan, out);
    std::cout << "[" << elapsed() << "]\n";
    const std::vector<Scene> scenes = tradeoffScenes(plan);
    captureTradeoff(plan, scenes, out);
    std::cout << "[" << elapsed() << "]\n";
    Fig12Input fig12Input;
    modelingAccuracy(plan, out, fig12Input);
    std::cout << "[" << elapsed() << "]\n";
    modelingTradeoff(plan, scenes, out);
    std::cout << "[" << elapsed() << "]\n";
    fig12(fig12Input, out);
    std::cout << "done in " << elapsed() << '\n';
    return 0;
}

}  // namespace
}  // namespace meadow::bench

int main(int argc, char** argv) {
    setenv("OMP_NUM_THREADS", "1", 1);            // before any OpenMP region (PCL): one thread
    meadow::capture::keepFrameBuffersResident();  // timed as the `meadow` command runs
    try {
        return meadow::bench::run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "accuracy_tradeoff_bench: " << e.what() << '\n';
        return 1;
    }
}
