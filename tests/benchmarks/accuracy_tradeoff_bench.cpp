// Accuracy against speed, measured against the simulated sensor's ground truth
// (docs/testing.md#measurements). Synthetic tufts (synth/synthetic_tuft.h presets, rendered in
// memory through synth::SimulatedSensor exactly as `meadow synth` does) go through the segmenter
// and the blade fit; the result is compared with the exact truth. Writes, under --out (default
// docs/measurements), the tables listed in accuracy_tradeoff/tables.h.
// Charts are drawn by tools/chart.sh (gnuplot). Times are wall time (std::chrono::steady_clock),
// median over repetitions, one thread; the thread's CPU time is written beside it because the
// wall time of the same work varies on a shared, loaded machine.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "accuracy_tradeoff/plan.h"
#include "accuracy_tradeoff/scene.h"
#include "accuracy_tradeoff/tables.h"
#include "common/report.h"
#include "meadow/capture/frame_memory.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::bench {

Plan makePlan(bool quick) {
    Plan plan;
    for (const auto& p : synth::synthPresets()) plan.segmentationPresets.push_back(p.name);
    if (quick) {
        plan.segmentationPresets = {"quadratic-leaf", "touching", "thin"};
        plan.bladeTypes = {"quadratic-leaf", "sharp-tip"};
        plan.noises = {0.f, 1.f};
        plan.distances_m = {0.8f};
        plan.segmentationDistances_m = {0.5f, 0.8f};
        plan.segmentationSeeds = 1;
        plan.modelingSeeds = 1;
        plan.tradeoffSeeds = 1;
        plan.repetitions = 1;
        plan.fusionFrames = {1, 3};
        plan.fusionSeeds = 1;
        plan.missedFrames = {1};
        plan.ablationSeeds = 1;
        plan.trackSeeds = 1;
        plan.motionSeeds = 1;
        plan.gentlerWinds = {0.f, 0.1f};
    }
    return plan;
}

namespace {

namespace fs = std::filesystem;

// What --only can name.
const std::vector<std::string> kTables{
    "segmentation-accuracy", "capture-tradeoff", "modeling-tradeoff",   "modeling-accuracy",
    "segmentation-distance", "modeling-groups",  "segmentation-fusion", "segmentation-missed",
    "segmentation-ablation", "tracks-fusion",    "tip-reach",           "motion-calibration"};

int run(int argc, char** argv) {
    fs::path out = "docs/measurements";
    bool quick = false, verbose = false;
    std::string only;  // one table's name, or every table
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick") {
            quick = true;
        } else if (arg == "--verbose") {
            verbose = true;
        } else if (arg == "--out" && i + 1 < argc) {
            out = argv[++i];
        } else if (arg == "--made" && i + 1 < argc) {
            setMadeLine(argv[++i]);
        } else if (arg == "--only" && i + 1 < argc &&
                   std::find(kTables.begin(), kTables.end(), argv[i + 1]) != kTables.end()) {
            only = argv[++i];
        } else {
            std::cerr << "usage: " << argv[0]
                      << " [--out DIR] [--quick] [--verbose] [--only T] [--made TEXT]\n"
                      << "  --out DIR  where the CSV, MD and PNG files go (default "
                         "docs/measurements)\n"
                      << "  --made TEXT  provenance line ending each Markdown table (commit, "
                         "date, machine)\n"
                      << "  --quick    fewer presets, seeds and repetitions: a smoke run\n"
                      << "  --verbose  one line per fitted blade (modeling accuracy)\n"
                      << "  --only T   one table (its files alone are rewritten):";
            for (const std::string& t : kTables) std::cerr << ' ' << t;
            std::cerr << '\n';
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
    const auto wanted = [&](const char* table) { return only.empty() || only == table; };
    const auto ran = [&] { std::cout << "[" << elapsed() << "]\n"; };
    if (wanted("segmentation-accuracy")) {
        segmentationAccuracy(plan, out);
        ran();
    }
    if (wanted("capture-tradeoff") || wanted("modeling-tradeoff")) {
        const std::vector<Scene> scenes = tradeoffScenes(plan);
        if (wanted("capture-tradeoff")) {
            captureTradeoff(plan, scenes, out);
            ran();
        }
        if (wanted("modeling-tradeoff")) {
            modelingTradeoff(plan, scenes, out);
            ran();
        }
    }
    if (wanted("modeling-accuracy")) {  // Fig. 12 runs on the skeletons its fits extracted
        Fig12Input fig12Input;
        modelingAccuracy(plan, out, fig12Input);
        fig12(fig12Input, out);
        ran();
    }
    if (wanted("segmentation-distance")) {
        segmentationOverDistance(plan, out);
        ran();
    }
    if (wanted("modeling-groups")) {
        modelingOverGroups(plan, out);
        ran();
    }
    const std::vector<std::pair<const char*, void (*)(const Plan&, const fs::path&)>> more{
        {"segmentation-fusion", segmentationOverFusion},
        {"segmentation-missed", segmentationMissed},
        {"segmentation-ablation", segmentationAblation},
        {"tracks-fusion", tracksOverFusion},
        {"tip-reach", tipReach},
        {"motion-calibration", motionCalibration}};
    for (const auto& [name, table] : more)
        if (wanted(name)) {
            table(plan, out);
            ran();
        }
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
