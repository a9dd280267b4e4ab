// Segmentation accuracy against the simulated sensor's ground truth (capture's Segmenter on
// modeling's synthetic tuft presets; it lives under tests/modeling/ because the presets do).
// A found blade matches a true one when their pixel IoU >= 0.5 (one-to-one, greedy by IoU).
// Target at nominal noise on the five blade-type presets: recall >= 0.95, median IoU >= 0.85
// (not met yet: that test is disabled; a floor of today's accuracy is asserted instead).
// MEADOW_SEGMENTATION_TABLE=1 prints the full preset x noise table (README's numbers);
// MEADOW_SEGMENTATION_DEBUG=<folder> writes each frame's overlay and, with
// MEADOW_SEGMENTATION_VERBOSE=1, a difference image per frame (missed red, extra blue, given to
// another blade yellow, in-band readings the mask left out green) and where the pixels went;
// MEADOW_SEGMENTATION_ABLATION=1 prints recall / median IoU with one sensor noise term off at a
// time (README: where the IoU goes); MEADOW_SEGMENTATION_ORACLE=1 has the floor test and the
// fusion table print the recall and median IoU each preset would reach if every found pixel on a
// true blade went to that blade (what a perfect partition of the found mask would give): where
// that recall is 1, the mask holds every blade and the partition loses them.
// MEADOW_SEGMENTATION_MISSED=1 prints, for every true blade no found one matches, what the
// sensor left to tell it apart by (PrintsWhatTheSensorLeftOfMissedBlades).
// MEADOW_SEGMENTATION_TOLERANT=1 scores every table with a one-pixel tolerance: a found pixel
// within a pixel (8-neighbourhood) of a true blade counts as on it, and a true pixel within a
// pixel of a found blade as found (the intersection is the mean of the two counts). For blades
// 1-3 px wide, lateral noise of 0.8 px alone keeps the plain IoU of a traced blade under 0.5.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "meadow/capture/segmenter.h"
#include "meadow/synth/simulated_sensor.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow {
namespace {

using capture::Segmentation;

constexpr double kMatchIou = 0.5;
constexpr double kTargetRecall = 0.95;
constexpr double kTargetMedianIou = 0.85;
const std::vector<std::string> kBladeTypePresets{"slim-grass", "quadratic-leaf", "shrub-leaf",
                                                 "bamboo-leaf", "sharp-tip"};
constexpr int kSeedsPerPreset = 2;

// The upper middle value (0 for none).
double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

// What the sensor left of a true blade that no found blade matched: how much of it was read on
// its surface, in how many pieces, and whether a depth step parts it from the blades it touches.
struct MissedBlade {
    double readShare = 0;      // share of its pixels read within kOnSurface_mm of its surface
    int readPieces = 0;        // 8-connected pieces those readings form
    int contact_px = 0;        // its pixels that 4-touch another blade's (in the noise-free view)
    double steppedShare = 0;   // share of those where the depth steps by >= kDepthStep_mm
    double medianStep_mm = 0;  // median step over the contact
};
constexpr float kOnSurface_mm = 10.f;
// 3.6 sigma of the axial noise at 0.7 m (1.37 mm); the quantisation step there is 1.4 mm.
constexpr float kDepthStep_mm = 5.f;

MissedBlade describeMissed(const cv::Mat1w& labels, const cv::Mat1f& exact_m,
                           const cv::Mat1w& depth_mm, int id) {
    MissedBlade m;
    const cv::Mat1b mine = labels == id;
    const int area_px = cv::countNonZero(mine);
    cv::Mat1f reading;
    depth_mm.convertTo(reading, CV_32F, 0.001);
    const cv::Mat1b onSurface =
        mine & (depth_mm > 0) & (cv::abs(reading - exact_m) <= kOnSurface_mm / 1000.f);
    m.readShare = area_px ? double(cv::countNonZero(onSurface)) / area_px : 0.0;
    cv::Mat1i pieces;
    m.readPieces = cv::connectedComponents(onSurface, pieces, 8) - 1;
    std::vector<double> steps;
    for (int y = 1; y + 1 < labels.rows; ++y)
        for (int x = 1; x + 1 < labels.cols; ++x) {
            if (labels(y, x) != id) continue;
            float step = -1.f;  // the largest step to a touching blade, -1 for none
            for (const cv::Point q : {cv::Point(x + 1, y), cv::Point(x - 1, y), cv::Point(x, y + 1),
                                      cv::Point(x, y - 1)})
                if (labels(q) != 0 && labels(q) != id)
                    step = std::max(step, 1000.f * std::abs(exact_m(q) - exact_m(y, x)));
            if (step >= 0.f) steps.push_back(static_cast<double>(step));
        }
    m.contact_px = static_cast<int>(steps.size());
    if (!steps.empty()) {
        m.steppedShare = double(std::count_if(steps.begin(), steps.end(),
                                              [](double d) { return d >= kDepthStep_mm; })) /
                         static_cast<double>(steps.size());
        m.medianStep_mm = median(steps);
    }
    return m;
}

struct Score {
    int truth = 0, found = 0, matched = 0;
    std::vector<double> iou;  // per matched true blade... and 0 for missed ones
    std::vector<double>
        oracleIou;  // the same with a perfect partition (MEADOW_SEGMENTATION_ORACLE)
    std::vector<std::string> flags;
    std::vector<MissedBlade> missed;  // with MEADOW_SEGMENTATION_MISSED
    void add(const Score& o) {
        truth += o.truth;
        found += o.found;
        matched += o.matched;
        iou.insert(iou.end(), o.iou.begin(), o.iou.end());
        oracleIou.insert(oracleIou.end(), o.oracleIou.begin(), o.oracleIou.end());
        flags.insert(flags.end(), o.flags.begin(), o.flags.end());
        missed.insert(missed.end(), o.missed.begin(), o.missed.end());
    }
    [[nodiscard]] double recall() const { return truth ? double(matched) / truth : 1.0; }
    [[nodiscard]] double precision() const { return found ? double(matched) / found : 1.0; }
    [[nodiscard]] double medianIou() const { return median(iou); }
    [[nodiscard]] double oracleRecall() const {
        const auto n = std::count_if(oracleIou.begin(), oracleIou.end(),
                                     [](double x) { return x >= kMatchIou; });
        return oracleIou.empty() ? 0.0 : double(n) / static_cast<double>(oracleIou.size());
    }
};

// Greedy one-to-one matching by IoU over every (true, found) pair.
Score score(const cv::Mat1w& labels, const Segmentation& s, const cv::Mat1w* depth_mm = nullptr,
            const cv::Mat1f* exact_m = nullptr) {
    double maxLabel = 0;
    cv::minMaxLoc(labels, nullptr, &maxLabel);
    Score sc;
    std::vector<int> ids;
    for (int id = 1; id <= static_cast<int>(maxLabel); ++id)
        if (cv::countNonZero(labels == id) > 0) ids.push_back(id);
    sc.truth = static_cast<int>(ids.size());
    sc.found = static_cast<int>(s.blades.size());
    struct Pair {
        double iou;
        size_t t, f;
    };
    std::vector<Pair> pairs;
    std::vector<cv::Mat1b> foundMasks;
    for (const auto& b : s.blades) foundMasks.push_back(b.frameMask(labels.size()));
    const bool tolerant = std::getenv("MEADOW_SEGMENTATION_TOLERANT") != nullptr;
    const auto grown = [](const cv::Mat1b& m) {
        cv::Mat1b g;
        cv::dilate(m, g, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
        return g;
    };
    std::vector<cv::Mat1b> foundGrown;
    if (tolerant)
        for (const auto& m : foundMasks) foundGrown.push_back(grown(m));
    for (size_t t = 0; t < ids.size(); ++t) {
        const cv::Mat1b truth = labels == ids[t];
        const cv::Mat1b truthGrown = tolerant ? grown(truth) : cv::Mat1b();
        for (size_t f = 0; f < s.blades.size(); ++f) {
            const double inter = tolerant ? (cv::countNonZero(foundMasks[f] & truthGrown) +
                                             cv::countNonZero(truth & foundGrown[f])) /
                                                2.0
                                          : cv::countNonZero(truth & foundMasks[f]);
            if (inter == 0) continue;
            const double uni = cv::countNonZero(truth) + cv::countNonZero(foundMasks[f]) - inter;
            pairs.push_back({inter / uni, t, f});
        }
    }
    std::sort(pairs.begin(), pairs.end(),
              [](const Pair& a, const Pair& b) { return a.iou > b.iou; });
    std::vector<double> best(ids.size(), 0.0);
    std::vector<int> pieceOf(ids.size(), -1);  // the found blade each true one was paired with
    std::vector<char> fUsed(s.blades.size(), 0);
    for (const auto& p : pairs) {
        if (pieceOf[p.t] >= 0 || fUsed[p.f]) continue;
        pieceOf[p.t] = static_cast<int>(p.f);
        fUsed[p.f] = 1;
        best[p.t] = p.iou;
        if (p.iou >= kMatchIou) ++sc.matched;
    }
    sc.iou = best;
    if (depth_mm && exact_m && std::getenv("MEADOW_SEGMENTATION_MISSED"))
        for (size_t t = 0; t < ids.size(); ++t)
            if (best[t] < kMatchIou)
                sc.missed.push_back(describeMissed(labels, *exact_m, *depth_mm, ids[t]));
    cv::Mat1b found = cv::Mat1b::zeros(labels.size());
    for (const auto& m : foundMasks) found |= m;
    const cv::Mat1b truthAny = labels > 0;
    if (std::getenv("MEADOW_SEGMENTATION_ORACLE")) {
        // Each true blade gets every found pixel on it; the found piece it was paired with keeps
        // its pixels off every true blade (the mask's own error stays).
        for (size_t t = 0; t < ids.size(); ++t) {
            const cv::Mat1b truth = labels == ids[t];
            cv::Mat1b mine = truth & found;
            if (pieceOf[t] >= 0) mine |= foundMasks[static_cast<size_t>(pieceOf[t])] & ~truthAny;
            const double u = cv::countNonZero(truth | mine);
            sc.oracleIou.push_back(u > 0 ? cv::countNonZero(truth & mine) / u : 0.0);
        }
    }
    if (std::getenv("MEADOW_SEGMENTATION_VERBOSE")) {
        // Where the IoU is lost, summed over blades: pixels of the cluster mask that no blade
        // owns in truth (mask too wide), true pixels outside the mask (mask too narrow), and
        // true pixels given to another blade (partition error).
        const int extra = cv::countNonZero(found & ~truthAny);
        const int missed = cv::countNonZero(truthAny & ~found);
        int misassigned = 0;
        cv::Mat1b wrongBlade = cv::Mat1b::zeros(labels.size());
        for (size_t t = 0; t < ids.size(); ++t) {
            if (pieceOf[t] < 0) continue;
            const cv::Mat1b wrong =
                (labels == ids[t]) & found & ~foundMasks[static_cast<size_t>(pieceOf[t])];
            misassigned += cv::countNonZero(wrong);
            wrongBlade |= wrong;
        }
        if (const char* folder = std::getenv("MEADOW_SEGMENTATION_DEBUG")) {
            // Missed true pixels red, extra mask pixels blue, correct ones grey.
            cv::Mat3b diff(labels.size(), cv::Vec3b(0, 0, 0));
            diff.setTo(cv::Vec3b(128, 128, 128), truthAny & found);
            diff.setTo(cv::Vec3b(0, 0, 255), truthAny & ~found);
            diff.setTo(cv::Vec3b(255, 0, 0), found & ~truthAny);
            diff.setTo(cv::Vec3b(0, 255, 255), wrongBlade);  // yellow: given to another blade
            if (depth_mm) {  // green: in-band readings the mask left out
                const cv::Mat1b inBand = (*depth_mm >= s.nearDepth_m * 1000.0) &
                                         (*depth_mm <= s.farDepth_m * 1000.0) & ~found;
                diff.setTo(cv::Vec3b(0, 160, 0), inBand & ~truthAny);
                diff.setTo(cv::Vec3b(0, 255, 0), inBand & truthAny);
            }
            static int counter = 0;
            // Cropped to the tuft and enlarged 3x, so single pixels can be seen.
            const cv::Rect box =
                (cv::boundingRect(truthAny | found) + cv::Size(20, 20) - cv::Point(10, 10)) &
                cv::Rect({}, labels.size());
            cv::Mat3b crop;
            cv::resize(diff(box), crop, {}, 3, 3, cv::INTER_NEAREST);
            cv::imwrite(std::string(folder) + "/diff_" + std::to_string(counter++) + ".png", crop);
        }
        std::cout << "    pixels: truth " << cv::countNonZero(truthAny) << ", found "
                  << cv::countNonZero(found) << ", extra " << extra << ", missed " << missed
                  << ", misassigned " << misassigned << '\n';
    }
    for (const auto& b : s.blades)
        for (const auto& r : b.reasons) sc.flags.push_back(r);
    for (const auto& c : s.clusters)
        for (const auto& r : c.reasons) sc.flags.push_back("cluster " + r);
    return sc;
}

// distance_m = 0: the preset's own camera distance.
Score run(const std::string& presetName, float noiseScale, std::uint64_t seed,
          const capture::SegmenterParams& params = {}, int fusedFrames = 1,
          void (*adjustNoise)(synth::NoiseModel&) = nullptr, float distance_m = 0.f) {
    const auto* preset = synth::findSynthPreset(presetName);
    if (!preset) throw std::invalid_argument("no preset " + presetName);
    synth::TuftParams tp;
    tp.seed = seed;
    tp.distance_m = distance_m;
    const auto spec = synth::buildPresetSpec(*preset, tp);
    const auto tuft = synth::buildTuft(spec, 0);
    synth::NoiseModel noise;
    noise.scale = noiseScale * preset->noiseMultiplier;
    if (adjustNoise) adjustNoise(noise);
    const synth::SimulatedSensor sensor(spec.camera.intrinsics, noise);
    const auto sim = sensor.render(tuft.meshes(), seed);
    // A still tuft seen over several frames: the same meshes, independent sensor noise.
    std::vector<capture::DepthFrame> frames(static_cast<size_t>(fusedFrames));
    for (int k = 0; k < fusedFrames; ++k) {
        auto& f = frames[static_cast<size_t>(k)];
        f.index = k;
        f.depth_mm =
            k == 0 ? sim.depth_mm
                   : sensor.render(tuft.meshes(), seed * 1000 + static_cast<unsigned>(k)).depth_mm;
        f.intrinsics = spec.camera.intrinsics;
    }
    const capture::DepthFrame& frame = frames.front();
    capture::SegmenterParams used = params;
    if (const char* ref = std::getenv("MEADOW_SEGMENTATION_REFERENCE");
        ref && std::string(ref) == "centre")
        used.reference = capture::ReferencePoint::ContourCentre;  // for the README's comparison
    const Segmentation s = capture::Segmenter(used).segment(frames);
    if (const char* folder = std::getenv("MEADOW_SEGMENTATION_DEBUG"))
        capture::writeDebugOverlay(
            std::filesystem::path(folder) / (presetName + "_n" + std::to_string(noiseScale) + "_s" +
                                             std::to_string(seed) + ".png"),
            frame, s);
    if (std::getenv("MEADOW_SEGMENTATION_VERBOSE")) std::cout << presetName << ' ' << s.summary();
    if (std::getenv("MEADOW_SEGMENTATION_VERBOSE")) {
        const cv::Mat1b truthAny = sim.labels > 0;
        const cv::Mat1b noReading = sim.depth_mm == 0;
        std::cout << "    true pixels without a reading: " << cv::countNonZero(truthAny & noReading)
                  << " of " << cv::countNonZero(truthAny) << '\n';
        cv::Mat1b found = cv::Mat1b::zeros(sim.labels.size());
        for (const auto& b : s.blades) found |= b.frameMask(sim.labels.size());
        cv::Mat1f reading;
        sim.depth_mm.convertTo(reading, CV_32F, 0.001);
        const cv::Mat1b displaced = cv::abs(reading - sim.exact_m) > 0.02f;
        const cv::Mat1b missed = truthAny & ~found;
        std::cout << "    missed: " << cv::countNonZero(missed) << " = no reading "
                  << cv::countNonZero(missed & noReading) << " + reading off the surface "
                  << cv::countNonZero(missed & ~noReading & displaced) << " + good reading "
                  << cv::countNonZero(missed & ~noReading & ~displaced) << '\n';
        const cv::Mat1b extra = found & ~truthAny;
        std::cout << "    extra: " << cv::countNonZero(extra) << " of which with no reading "
                  << cv::countNonZero(extra & noReading) << '\n';
    }
    return score(sim.labels, s, &frames.front().depth_mm, &sim.exact_m);
}

// The brief's target, not met yet (see README's segmentation table), on one frame: slim-grass
// blades (1.4-3.6 px wide at 0.8 m) fall apart under the sensor's lateral noise and lie along or
// across one another (recall 0.22; from 12 frames fused by their nearest recurring readings 0.47
// over seeds 1-5, where a perfect partition of the same mask would match 0.91), sharp-tip's
// smallest blade lies along a neighbour at its depth and comes out merged with it (recall 0.83),
// and on one frame the leaves reach a median IoU of 0.81-0.92 (quadratic and bamboo meet 0.85; all
// four do from 12 frames fused by recurring readings:
// LeavesFromTwelveFramesFusedByRecurringReadingsMeetTheIouTarget). Disabled until then.
TEST(SegmentationAccuracy, DISABLED_BladeTypePresetsAtNominalNoiseMeetRecallAndIouTargets) {
    for (const auto& preset : kBladeTypePresets) {
        Score total;
        for (int seed = 1; seed <= kSeedsPerPreset; ++seed)
            total.add(run(preset, 1.0f, static_cast<std::uint64_t>(seed)));
        EXPECT_GE(total.recall(), kTargetRecall)
            << preset << ": " << total.matched << "/" << total.truth;
        EXPECT_GE(total.medianIou(), kTargetMedianIou) << preset;
    }
}

// What is achieved today, held as a floor so it cannot silently get worse: the four leaf
// presets at nominal noise, one frame (measured recall 0.83-1.0, median IoU 0.82-0.92; 0.78-0.88
// before the fork zone was decided by depth).
TEST(SegmentationAccuracy, LeafPresetsAtNominalNoiseKeepTodaysAccuracy) {
    constexpr double kFloorRecall = 0.8;
    constexpr double kFloorMedianIou = 0.80;
    for (const std::string preset : {"quadratic-leaf", "shrub-leaf", "bamboo-leaf", "sharp-tip"}) {
        Score total;
        for (int seed = 1; seed <= kSeedsPerPreset; ++seed)
            total.add(run(preset, 1.0f, static_cast<std::uint64_t>(seed)));
        EXPECT_GE(total.recall(), kFloorRecall)
            << preset << ": " << total.matched << "/" << total.truth;
        EXPECT_GE(total.medianIou(), kFloorMedianIou) << preset;
        std::cout << "  " << preset << ": recall " << total.recall() << " precision "
                  << total.precision() << " median IoU " << total.medianIou();
        if (!total.oracleIou.empty())
            std::cout << ", with a perfect partition recall " << total.oracleRecall()
                      << " median IoU " << median(total.oracleIou);
        std::cout << '\n';
    }
}

// Twelve frames of a still tuft fused by their nearest recurring readings (FusionMethod::
// NearestRecurring): a thin tip or edge read as blade in 5 of the 12 frames is kept, where
// the median kept the wall. The four leaf presets then meet the target median IoU (measured,
// seeds 1-2: 0.93 / 0.91 / 0.95 / 0.87; by the median of the same 12 frames 0.91 / 0.87 / 0.94 /
// 0.83), and all but sharp-tip the target recall (its smallest blade lies along a neighbour at
// the same depth and stays merged: 0.83).
TEST(SegmentationAccuracy, LeavesFromTwelveFramesFusedByRecurringReadingsMeetTheIouTarget) {
    capture::SegmenterParams recurring;
    recurring.fusion = capture::FusionMethod::NearestRecurring;
    for (const std::string preset : {"quadratic-leaf", "shrub-leaf", "bamboo-leaf", "sharp-tip"}) {
        Score total;
        for (int seed = 1; seed <= kSeedsPerPreset; ++seed)
            total.add(run(preset, 1.0f, static_cast<std::uint64_t>(seed), recurring, 12));
        std::cout << "  " << preset << ": recall " << total.recall() << " median IoU "
                  << total.medianIou() << '\n';
        EXPECT_GE(total.medianIou(), kTargetMedianIou) << preset;
        EXPECT_GE(total.recall(), preset == "sharp-tip" ? 0.8 : kTargetRecall) << preset;
    }
}

// Seen from close up a tuft spans most of the image columns, as ground and walls seen edge-on
// do; only what also reaches both side borders, or lies in stripes across the frame, is skipped
// as scenery now. Measured
// (1x, one frame, seeds 1-5), before -> after: shrub-leaf at 0.6 m recall 0.20 -> 1.00, at
// 0.5 m 0.00 -> 1.00; slim grass at 0.6 m 0.18 -> 0.36, at 0.5 m 0.00 -> 0.53 (seeds 1-2, as
// here: shrub-leaf 0.50 -> 1.00, slim grass 0.00 -> 0.61).
TEST(SegmentationAccuracy, ATuftSeenFromCloseUpIsFound) {
    Score shrub, slim;
    for (int seed = 1; seed <= kSeedsPerPreset; ++seed) {
        shrub.add(run("shrub-leaf", 1.0f, static_cast<std::uint64_t>(seed), {}, 1, nullptr, 0.6f));
        slim.add(run("slim-grass", 1.0f, static_cast<std::uint64_t>(seed), {}, 1, nullptr, 0.5f));
    }
    std::cout << "  shrub-leaf at 0.6 m: recall " << shrub.recall() << ", median IoU "
              << shrub.medianIou() << "; slim grass at 0.5 m: recall " << slim.recall() << '\n';
    EXPECT_GE(shrub.recall(), 0.9);
    EXPECT_GE(shrub.medianIou(), 0.8);
    EXPECT_GE(slim.recall(), 0.3);
}

// Where the edges are ragged (2x noise: 4-8 % against 0.4-1.3 % at 1x) the continued centre
// lines of the fork zone lose (shrub-leaf 0.55 -> 0.52 in the measurement), so the wedges stand
// there; at nominal noise deciding the zone by depth lifts the leaves' median IoU.
TEST(SegmentationAccuracy, ForkZoneIsDecidedByDepthWhereTheEdgesAreClean) {
    capture::SegmenterParams wedgeOnly;
    wedgeOnly.forkByDepth = false;
    for (int seed = 1; seed <= kSeedsPerPreset; ++seed) {
        const Score fork = run("shrub-leaf", 2.0f, static_cast<std::uint64_t>(seed));
        const Score wedge = run("shrub-leaf", 2.0f, static_cast<std::uint64_t>(seed), wedgeOnly);
        EXPECT_EQ(fork.iou, wedge.iou) << "2x noise, seed " << seed;
    }
    for (const std::string preset : {"quadratic-leaf", "bamboo-leaf"}) {
        Score fork, wedge;
        for (int seed = 1; seed <= kSeedsPerPreset; ++seed) {
            fork.add(run(preset, 1.0f, static_cast<std::uint64_t>(seed)));
            wedge.add(run(preset, 1.0f, static_cast<std::uint64_t>(seed), wedgeOnly));
        }
        std::cout << "  " << preset << ": median IoU " << wedge.medianIou() << " -> "
                  << fork.medianIou() << '\n';
        EXPECT_GE(fork.medianIou(), wedge.medianIou() + 0.02) << preset;  // measured +0.04-0.05
    }
}

// Slim grass (1.4-3.6 px wide blades at 0.8 m) reaches the segmentation as stalks joined to the
// tuft and fragments farther up, each under half a blade: no blade matched at nominal noise.
// Joining the fragments back (fragment_links.cpp) matches some (measured 4 of 18, seeds 1-2).
TEST(SegmentationAccuracy, BrokenSlimGrassBladesAreJoinedBack) {
    capture::SegmenterParams unlinked;
    unlinked.fragmentLinkGap_px = 0.f;
    Score linked, apart;
    for (int seed = 1; seed <= kSeedsPerPreset; ++seed) {
        linked.add(run("slim-grass", 1.0f, static_cast<std::uint64_t>(seed)));
        apart.add(run("slim-grass", 1.0f, static_cast<std::uint64_t>(seed), unlinked));
    }
    std::cout << "  slim-grass: recall " << apart.recall() << " -> " << linked.recall()
              << ", median IoU " << apart.medianIou() << " -> " << linked.medianIou() << '\n';
    EXPECT_GE(linked.matched, apart.matched + 2);
    EXPECT_GE(linked.recall(), 0.15);
}

// A plane fitted to the narrow strip of ground the sensor still reads is loose in pitch and
// roll; on these two (found in the README's measurement run) it left a strip of near ground
// 10-25 mm off the plane, nearer than the tuft, and the automatic band took that strip for the
// tuft (recall 0). The band now skips a depth mode whose points form a flat, level patch.
TEST(SegmentationAccuracy, GroundLeftByThePlaneFitIsNotTakenForTheTuft) {
    for (const auto& [preset, seed] :
         std::vector<std::pair<std::string, int>>{{"bamboo-leaf", 1}, {"sharp-tip", 2}}) {
        const Score sc = run(preset, 1.0f, static_cast<std::uint64_t>(seed), {}, 3);
        EXPECT_GE(sc.recall(), 0.8) << preset << " seed " << seed;
        EXPECT_GE(sc.precision(), 0.8) << preset << " seed " << seed;
    }
}

// The camera 35 deg above the horizontal, looking down: the plane fit removes the ground, and the
// wall behind begins 1 cm beyond the farthest blade. The histogram's smoothing merged the wall's
// mode with the tuft's and the merged mode was skipped as scenery: no blades at 1x noise (5 of 5
// frames). The band is now looked for again without the depth bins that alone span the frame
// (measured seeds 1-2: recall 0.58, precision 0.70; the wall is no blade).
TEST(SegmentationAccuracy, ATiltedCameraFindsTheTuftInFrontOfTheWall) {
    Score total;
    for (int seed = 1; seed <= kSeedsPerPreset; ++seed)
        total.add(run("tilted", 1.0f, static_cast<std::uint64_t>(seed)));
    std::cout << "  tilted: recall " << total.recall() << " precision " << total.precision()
              << " median IoU " << total.medianIou() << '\n';
    EXPECT_GE(total.recall(), 0.5) << total.matched << "/" << total.truth;
    EXPECT_GE(total.precision(), 0.6) << total.matched << "/" << total.found;
}

// Which sensor term costs the IoU: nominal noise with one term switched off at a time.
TEST(SegmentationAccuracy, PrintsNoiseTermAblation) {
    if (!std::getenv("MEADOW_SEGMENTATION_ABLATION"))
        GTEST_SKIP() << "set MEADOW_SEGMENTATION_ABLATION=1";
    using Adjust = void (*)(synth::NoiseModel&);
    const std::vector<std::pair<std::string, Adjust>> terms{
        {"all terms", nullptr},
        {"no axial", [](synth::NoiseModel& n) { n.axial = false; }},
        {"no lateral", [](synth::NoiseModel& n) { n.lateral = false; }},
        {"no quantisation", [](synth::NoiseModel& n) { n.quantisation = false; }},
        {"no shadows", [](synth::NoiseModel& n) { n.shadows = false; }},
        {"no grazing", [](synth::NoiseModel& n) { n.grazingDropout = false; }},
        {"no flying", [](synth::NoiseModel& n) { n.flyingPixels = false; }},
        {"lateral only",
         [](synth::NoiseModel& n) {
             n.axial = n.quantisation = n.shadows = n.grazingDropout = n.flyingPixels = false;
         }},
    };
    std::cout << "| term |";
    for (const auto& p : kBladeTypePresets) std::cout << ' ' << p << " |";
    std::cout << '\n';
    for (const auto& [name, adjust] : terms) {
        std::cout << "| " << name << " |";
        for (const auto& preset : kBladeTypePresets) {
            Score total;
            for (int seed = 1; seed <= kSeedsPerPreset; ++seed)
                total.add(run(preset, 1.0f, static_cast<std::uint64_t>(seed), {}, 1, adjust));
            std::cout << std::fixed << std::setprecision(2) << ' ' << total.recall() << " / "
                      << total.medianIou() << " |";
        }
        std::cout << std::endl;
    }
}

TEST(SegmentationAccuracy, PrintsPresetByNoiseTable) {
    if (!std::getenv("MEADOW_SEGMENTATION_TABLE"))
        GTEST_SKIP() << "set MEADOW_SEGMENTATION_TABLE=1";
    std::vector<std::string> presets = kBladeTypePresets;
    for (const auto& p : synth::synthPresets())
        if (std::find(presets.begin(), presets.end(), p.name) == presets.end())
            presets.push_back(p.name);
    std::cout << "| preset | noise | recall | precision | median IoU | flags raised "
                 "|\n|---|---|---|---|---|---|\n";
    for (const auto& preset : presets)
        for (float noise : {0.f, 1.f, 2.f, 4.f}) {
            Score total;
            for (int seed = 1; seed <= kSeedsPerPreset; ++seed)
                total.add(run(preset, noise, static_cast<std::uint64_t>(seed)));
            std::map<std::string, int> kinds;
            for (const auto& f : total.flags) ++kinds[f.substr(0, f.find(':'))];
            std::string flags;
            for (const auto& [k, n] : kinds)
                flags += (flags.empty() ? "" : ", ") + k + " x" + std::to_string(n);
            std::cout << std::fixed << std::setprecision(2) << "| " << preset << " | " << noise
                      << "x | " << total.recall() << " | " << total.precision() << " | "
                      << total.medianIou() << " | " << flags << " |\n";
        }
}

// Recall / median IoU of the five blade-type presets at nominal noise against the number of
// fused frames of a still tuft, by median and by nearest recurring reading (README, "Fusing
// frames by recurring readings"). MEADOW_SEGMENTATION_SEEDS=N takes seeds 1-N (2 by default).
TEST(SegmentationAccuracy, PrintsFusionTable) {
    if (!std::getenv("MEADOW_SEGMENTATION_FUSION"))
        GTEST_SKIP() << "set MEADOW_SEGMENTATION_FUSION=1";
    const char* seedsVar = std::getenv("MEADOW_SEGMENTATION_SEEDS");
    const int seeds = seedsVar ? std::max(1, std::atoi(seedsVar)) : kSeedsPerPreset;
    std::cout << "| fusion | frames |";
    for (const auto& p : kBladeTypePresets) std::cout << ' ' << p << " |";
    std::cout << "\n|---|---|---|---|---|---|---|\n";
    for (const auto method :
         {capture::FusionMethod::Median, capture::FusionMethod::NearestRecurring})
        for (int fused : {1, 3, 5, 8, 12, 16}) {
            if (fused == 1 && method != capture::FusionMethod::Median) continue;
            capture::SegmenterParams params;
            params.fusion = method;
            std::cout << "| " << (fused == 1 ? "none" : capture::toString(method)) << " | " << fused
                      << " |";
            for (const auto& preset : kBladeTypePresets) {
                Score total;
                for (int seed = 1; seed <= seeds; ++seed)
                    total.add(run(preset, 1.0f, static_cast<std::uint64_t>(seed), params, fused));
                std::cout << std::fixed << std::setprecision(2) << ' ' << total.recall() << " / "
                          << total.medianIou();
                if (!total.oracleIou.empty())
                    std::cout << " (perfect partition " << total.oracleRecall() << " / "
                              << median(total.oracleIou) << ")";
                std::cout << " |";
            }
            std::cout << std::endl;
        }
}

// Why the blades that are missed are missed (README, "What the sensor leaves of the missed
// blades"): per preset at nominal noise, one frame, how much of each missed blade the sensor read
// on its surface and whether a depth step parts it from the blades it lies against. A blade read
// on under half its pixels, or touching its neighbours with no step over 3.6 sigma of the axial
// noise, leaves a partition of the depth image nothing to cut along.
TEST(SegmentationAccuracy, PrintsWhatTheSensorLeftOfMissedBlades) {
    if (!std::getenv("MEADOW_SEGMENTATION_MISSED"))
        GTEST_SKIP() << "set MEADOW_SEGMENTATION_MISSED=1";
    const char* seedsVar = std::getenv("MEADOW_SEGMENTATION_SEEDS");
    const int seeds = seedsVar ? std::max(1, std::atoi(seedsVar)) : kSeedsPerPreset;
    // MEADOW_SEGMENTATION_FRAMES=N: N frames fused by their nearest recurring readings (the read
    // share stays that of the first frame).
    const char* framesVar = std::getenv("MEADOW_SEGMENTATION_FRAMES");
    const int frames = framesVar ? std::max(1, std::atoi(framesVar)) : 1;
    capture::SegmenterParams params;
    if (frames > 1) params.fusion = capture::FusionMethod::NearestRecurring;
    std::cout << "| preset | missed / true | read on under half | touching, no step on 30 % of "
                 "the contact | neither | read share (median) | pieces read (median) | median step "
                 "(mm) |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& preset : kBladeTypePresets) {
        Score total;
        for (int seed = 1; seed <= seeds; ++seed)
            total.add(run(preset, 1.0f, static_cast<std::uint64_t>(seed), params, frames));
        std::vector<double> share, pieces, step;
        int underHalf = 0, noStep = 0, neither = 0;
        for (const auto& m : total.missed) {
            share.push_back(m.readShare);
            pieces.push_back(m.readPieces);
            if (m.contact_px > 0) step.push_back(m.medianStep_mm);
            const bool little = m.readShare < 0.5;
            const bool flush = m.contact_px > 0 && m.steppedShare < 0.3;
            underHalf += little;
            noStep += flush;
            neither += !little && !flush;
        }
        std::cout << std::fixed << std::setprecision(2) << "| " << preset << " | "
                  << total.missed.size() << " / " << total.truth << " | " << underHalf << " | "
                  << noStep << " | " << neither << " | " << median(share) << " | " << median(pieces)
                  << " | " << median(step) << " |" << std::endl;
    }
}

}  // namespace
}  // namespace meadow
