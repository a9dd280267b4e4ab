// `meadow capture`: a depth source -> an archetype library (JSON, optionally .glb).
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "meadow/capture/depth_source.h"
#include "meadow/modeling/archetype_glb.h"
#include "meadow/modeling/capture_pipeline.h"
#include "progress.h"
#include "source_options.h"

namespace meadow::cli {

namespace {

struct CaptureArgs {
    std::string source;
    std::string out;
    std::string glb;
    std::string debug;
    SourceArgs sourceArgs;
    modeling::CaptureOptions options;
    float tolerance_mm = 0.f;
    std::string plane;
    std::string fusion = capture::toString(capture::FusionMethod::Median);
    bool verbose = false;
};

// Algorithm 1 keeps at least the blade's two ends: 0 (no refining) or 2 to 128 (the skeleton's
// points).
const CLI::Validator kRefinedKnotCount(
    [](std::string& value) {
        int knots = -1;
        try {
            knots = std::stoi(value);
        } catch (const std::exception&) {
            return std::string("not a whole number: " + value);
        }
        if (knots == 1)
            return std::string(
                "1 knot cannot be kept: 0 skips refining, otherwise at least 2 (the blade's two "
                "ends)");
        if (knots < 0 || knots > 128) return "out of 0-128: " + value;
        return std::string();
    },
    "in {0, 2-128}");

// A user band needs both edges, near below far (the segmenter's own check names its fields).
void checkBand(float near_m, float far_m) {
    if ((near_m > 0.f || far_m > 0.f) && !(near_m < far_m)) {
        std::ostringstream s;
        s << "the band's near edge (" << near_m << " m) must lie below its far edge (" << far_m
          << " m); give both, or neither for an automatic band";
        throw CLI::ValidationError("--near/--far", s.str());
    }
}

void runCapture(CaptureArgs& args) {
    checkBand(args.options.segmenter.nearDepth_m, args.options.segmenter.farDepth_m);
    modeling::CaptureOptions options = args.options;
    options.debugDir = args.debug;
    // The options' checks have already refused any other name.
    options.segmenter.planeMethod = *capture::kPlaneMethodNames.parse(args.plane);
    options.segmenter.fusion = *capture::kFusionMethodNames.parse(args.fusion);
    options.fit.setTolerance_m(args.tolerance_mm * 1e-3f);

    auto source = capture::openDepthSource(args.source, toSourceOptions(args.sourceArgs));
    const int frames = source->info().frameCount;
    Progress progress("capture", static_cast<std::size_t>(frames > 0 ? frames : 1));
    const modeling::CaptureResult result = modeling::captureArchetypes(
        *source, args.source, options,
        [&progress](int done, int) { progress.update(static_cast<std::size_t>(done)); });
    progress.finish();

    modeling::saveArchetypeLibrary(result.library, args.out);
    if (!args.glb.empty()) modeling::exportArchetypeGlb(result.library, args.glb);

    const auto& s = result.summary;
    std::cout << "captured " << s.bladesModelled << " of " << s.bladesFound << " blade(s) from "
              << s.framesRead << " frame(s) -> " << result.library.archetypes.size()
              << " archetype(s) in " << args.out << (args.glb.empty() ? "" : " and " + args.glb)
              << '\n';
    if (s.averagedArchetypes > 0)
        std::cout << s.averagedArchetypes << " archetype(s) fitted to a blade seen in several of "
                  << s.segmentations << " fused groups (the mean of its skeletons; --per-group "
                  << "keeps one archetype per group)\n";
    if (s.movingRuns > 0)
        std::cout << "the tuft moved in " << s.movingRuns << " of " << s.motionTests
                  << " run(s) of frames (" << s.motion
                  << "): those were segmented without recurring readings and modelled one "
                     "archetype per group (--assume-still takes every run for still)\n";
    if (const std::string skipped = modeling::skippedSummary(s); !skipped.empty())
        std::cout << skipped << '\n';
    if (!s.notes.empty()) {
        std::cout << s.notes.size() << " note(s)"
                  << (args.verbose ? ":" : " (--verbose lists them)") << '\n';
        if (args.verbose)
            for (const auto& note : s.notes) std::cout << "  " << note << '\n';
    }
}

}  // namespace

void addCaptureCommand(CLI::App& app) {
    // Options bound to the library's own fields show the library's defaults (capture_default_str)
    // rather than a copy of them that could drift.
    auto args = std::make_shared<CaptureArgs>();
    CLI::App* cmd = app.add_subcommand(
        "capture",
        "Cut the tuft seen by a depth source into single blades and model each as an archetype "
        "(quadratic Bezier spine + width profile): writes an archetype library");
    cmd->footer(
        "Camera distance, measured on the simulated presets (README, \"Segmentation over camera "
        "distance\"): leaf-like blades 6-25 mm wide segment well with the tuft 0.6-1.2 m away "
        "(recall 0.80-1.00); grass blades 2-5 mm wide are found best close (recall 0.40-0.53 at "
        "0.5 m, 0.24 at 0.8 m, 0 at 1.2 m). Aim the camera at the tuft from the side, its base in "
        "view: a camera a few centimetres above the ground, looking along it, can leave the ground "
        "unfitted. A still tuft is modelled better from more frames: record a dozen or more, and "
        "each blade becomes one archetype fitted to its views from every group of --fuse frames "
        "(README, \"One archetype per blade\"), and thin tips are followed through the readings "
        "that recur over --recurring-frames frames. Each such run of frames is first tested for "
        "motion: where the tuft moved (wind), its groups are segmented without the recurring "
        "readings and each blade of each group is its own archetype (README, \"A tuft that "
        "moves\").");
    cmd->add_option("SOURCE", args->source,
                    "Recording folder, plain folder of 16-bit PNGs (with --intrinsics and "
                    "--depth-unit), .oni file, or openni:// for a live camera")
        ->required();
    cmd->add_option("--out", args->out, "Archetype library JSON to write")->required();
    cmd->add_option("--glb", args->glb,
                    "Also write the library as glTF 2.0 binary (one mesh per archetype)");
    cmd->add_option("--debug", args->debug,
                    "Folder for an overlay PNG per segmentation (mask, contour, cuts, blades)");
    cmd->add_option("--fuse", args->options.fusionFrames,
                    "Frames fused (--fusion) per segmentation, for a still tuft; 1 = each "
                    "frame alone. Measured (median IoU, simulated presets): 1 frame 0.82, 2 0.81, "
                    "3 0.85, 5 0.86; an even count has no middle reading (README, \"Fusing an "
                    "even count\")")
        ->capture_default_str()
        ->check(CLI::Range(1, 64));
    cmd->add_option("--fusion", args->fusion,
                    "How --fuse frames become one: median (per pixel) or nearest-recurring (per "
                    "pixel the nearest depth that 34 % of the frames read alike, else the "
                    "median), which keeps thin blades and tips that the median hands to the "
                    "wall. For thin grass record 12 frames or more and pass --fuse 12 --fusion "
                    "nearest-recurring: measured on the simulated slim grass (0.6-1.0 m), tip "
                    "RMS 74 -> 21 mm; on leaves capture's default groups keep their tips nearer "
                    "(1.4-4.2 against 1.4-4.4 mm), though the masks are better (README, \"Fusing "
                    "frames by recurring readings\")")
        ->capture_default_str()
        ->check(CLI::IsMember(capture::kFusionMethodNames.names()));
    cmd->add_option("--max-frames", args->options.maxFrames,
                    "Stop after this many frames (0 = all)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    cmd->add_option(
           "--max-archetypes", args->options.maxArchetypes,
           "Merge near-duplicate blades until at most this many archetypes remain (0 = keep all)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    cmd->add_option(
           "--tolerance-mm", args->tolerance_mm,
           "Model no more than this needs: the fewest width samples whose mean error is within "
           "it, and the fewest refined knots (at most --knots) whose polyline stays within it in "
           "every simulated frame (0 = always 16 samples and --knots knots)")
        ->default_val(0.f)
        ->check(CLI::Range(0.f, 100.f));
    cmd->add_option("--knots", args->options.fit.refinedKnots,
                    "Skeleton knots kept by the movement-similarity refiner, the most kept under "
                    "--tolerance-mm (0 = no refining)")
        ->capture_default_str()
        ->check(kRefinedKnotCount);
    cmd->add_option("--near", args->options.segmenter.nearDepth_m,
                    "Near edge of the depth band in metres (0 with --far 0: automatic)")
        ->capture_default_str()
        ->check(CLI::Range(0.f, 20.f));
    cmd->add_option("--far", args->options.segmenter.farDepth_m,
                    "Far edge of the depth band in metres")
        ->capture_default_str()
        ->check(CLI::Range(0.f, 20.f));
    cmd->add_option("--plane", args->plane,
                    "Ground/background plane removal: ransac (PCL SACSegmentation), "
                    "organized-multi-plane (PCL OrganizedMultiPlaneSegmentation) or none")
        ->default_val(capture::toString(capture::SegmenterParams{}.planeMethod))
        ->check(CLI::IsMember(capture::kPlaneMethodNames.names()));
    cmd->add_option("--edge-smoothing", args->options.segmenter.edgeSmoothingSigma_px,
                    "Sigma, in contour points, of the Gaussian that smooths the mask's ragged edge "
                    "along its contour (0 = off; no point moves more than 1 px, tips and valleys "
                    "between blades stay)")
        ->capture_default_str()
        ->check(CLI::Range(0.f, 20.f));
    cmd->add_flag_callback(
        "--per-group", [args] { args->options.tracks.enabled = false; },
        "One archetype per blade and fused group, for a camera that moves between groups (runs "
        "in which the tuft moved are found by a motion test and modelled so already). "
        "By default a blade seen in several groups (its skeletons within " +
            std::to_string(static_cast<int>(
                std::lround(100.f * modeling::BladeTrackParams{}.maxDistanceFraction))) +
            " % of its length of each other) is fitted once, to the mean of its skeletons, which "
            "lies nearer the blade than any one of them (README, \"One archetype per blade\")");
    cmd->add_option(
           "--recurring-frames", args->options.recurringFrames,
           "Tip trails also follow readings that recur (in " +
               std::to_string(std::lround(100.f * capture::RecurringParams{}.minShare)) +
               " % of the frames, at least " +
               std::to_string(capture::RecurringParams{}.minFrames) + ", within " +
               std::to_string(capture::RecurringParams{}.agreement_mm) +
               " mm) over this many frames of a still tuft, where a thin tip is read a few "
               "times in different pixels; 0 = each group's own readings only. A run in which "
               "the tuft moved is segmented without them (--assume-still). Needs a recording "
               "of at least this many frames (README, \"Tips from readings that recur over "
               "frames\")")
        ->capture_default_str()
        ->check(CLI::Range(0, 64));
    cmd->add_flag_callback(
        "--assume-still", [args] { args->options.checkMotion = false; },
        "Take every run of --recurring-frames frames for a still tuft, without testing it for "
        "motion (the test: readings changed " +
            std::to_string(capture::MotionParams{}.farLag) +
            " frames apart against 1 apart; a tuft that moves from " +
            std::to_string(capture::MotionParams{}.movedRatio).substr(0, 3) + "x and " +
            std::to_string(std::lround(100.0 * capture::MotionParams{}.minMovedShare)) +
            " % of the readings more, still tufts measured 0.95-1.05x, wind 2.1-2.8x)");
    cmd->add_flag(
        "--keep-flagged", args->options.keepFlagged,
        "Also model blades the segmenter flagged (overlapping, curling, too thin, base hidden)");
    cmd->add_flag("--verbose", args->verbose,
                  "List every skipped blade and empty frame with its reason");
    addSourceOptions(*cmd, args->sourceArgs);
    cmd->callback([args] { runCapture(*args); });
}

}  // namespace meadow::cli
