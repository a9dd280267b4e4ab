// `meadow capture`: a depth source -> an archetype library (JSON, optionally .glb).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "meadow/capture/depth_source.h"
#include "meadow/core/atomic_file.h"
#include "meadow/modeling/archetype_glb.h"
#include "meadow/modeling/capture_pipeline.h"
#include "option_checks.h"
#include "output_checks.h"
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
    std::string subject = std::string(capture::kSubjectNames.name(capture::Subject::Tuft));
    // Given on the command line, these stand over the subject's choice.
    std::string findPlant;
    std::string partition;
    const CLI::Option* findPlantOption = nullptr;
    const CLI::Option* partitionOption = nullptr;
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

// The outputs are checked before any frame is read: a capture replaces a previous library or
// .glb of its own, never another file, and never one of its outputs by the other.
void checkOutputs(const CaptureArgs& args) {
    if (!args.glb.empty() && sameFile(args.out, args.glb))
        throw CLI::ValidationError(
            "--out/--glb", "both name " + args.out + "; give the library and the .glb two files");
    refuseToReplace(args.out, "--out", modeling::isArchetypeLibraryFile,
                    "it is not an archetype library");
    if (!args.glb.empty())
        refuseToReplace(args.glb, "--glb", modeling::isMeadowGlb, "it is not a .glb meadow wrote");
    if (!args.debug.empty())
        refuseFolderOfOthers(args.debug, "--debug", isOverlayName,
                             "it holds files that are not capture overlays");
    checkWritable(args.out);
    if (!args.glb.empty()) checkWritable(args.glb);
}

void runCapture(CaptureArgs& args) {
    checkBand(args.options.segmenter.nearDepth_m, args.options.segmenter.farDepth_m);
    checkOutputs(args);
    modeling::CaptureOptions options = args.options;
    options.debugDir = args.debug;
    // The options' checks have already refused any other name.
    options.segmenter.planeMethod = *capture::kPlaneMethodNames.parse(args.plane);
    options.segmenter.fusion = *capture::kFusionMethodNames.parse(args.fusion);
    options.segmenter.setSubject(*capture::kSubjectNames.parse(args.subject));
    if (args.findPlantOption->count() > 0)
        options.segmenter.plantFinding = *capture::kPlantFindingNames.parse(args.findPlant);
    if (args.partitionOption->count() > 0)
        options.segmenter.partition = *capture::kPartitionMethodNames.parse(args.partition);
    options.fit.setTolerance_m(args.tolerance_mm * 1e-3f);

    auto source = capture::openDepthSource(args.source, toSourceOptions(args.sourceArgs));
    const int frames = source->info().frameCount;
    Progress progress("capture", static_cast<std::size_t>(frames > 0 ? frames : 1));
    const modeling::CaptureResult result = modeling::captureArchetypes(
        *source, args.source, options,
        [&progress](int done, int) { progress.update(static_cast<std::size_t>(done)); });
    progress.finish();

    // Both outputs are written in full before either replaces what was there.
    AtomicFile library(args.out);
    library.stream() << modeling::serialiseArchetypeLibrary(result.library);
    std::optional<AtomicFile> glb;
    if (!args.glb.empty()) {
        glb.emplace(args.glb);
        glb->stream() << modeling::archetypeGlbBytes(result.library);
    }
    library.commit();
    if (glb) glb->commit();

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
                  << "): those frames were segmented one by one, without recurring readings, "
                  << (s.turningRuns == s.movingRuns ? "as views of a turning plant"
                      : s.turningRuns > 0
                          ? "those of " + std::to_string(s.turningRuns) +
                                " run(s) as views of a turning plant, the rest modelled one "
                                "archetype per group"
                          : std::string("and modelled one archetype per group"))
                  << " (--assume-still takes every run for still)\n";
    if (s.turningViews > 1)
        std::cout << "a turning plant: " << s.registeredViews << " of " << s.turningViews - 1
                  << " view(s) registered to the views before"
                  << (result.turningLoop.met() ? " and the last to the first" : "") << " ("
                  << s.viewChains << " chain(s)), " << s.joinedArchetypes
                  << " archetype(s) left out for a longer one of the same leaf (--per-group "
                     "keeps every view's)\n";
    if (s.turningViews > 1 && 2 * s.registeredViews < s.turningViews - 1)
        std::cout << "most views lay on no view before them, so each keeps its own leaves, "
                     "pieces and all: bring the camera closer (a leaf a few pixels wide is lost "
                     "to its mixed readings) or turn the plant by smaller steps; --verbose says "
                     "why each view was not registered (docs/capture.md#turntable-views)\n";
    if (const auto& stem = result.library.stem) {
        std::ostringstream height;
        height.precision(2);
        height << std::fixed << stem->height_m;
        std::cout << "stem " << height.str() << " m from its foot to the highest leaf's node "
                  << "(median of " << stem->views << " segmentation(s))\n";
    }
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
    // rather than a copy of them that could drift. One line an option; the why is in
    // docs/cli.md and docs/capture.md.
    auto args = std::make_shared<CaptureArgs>();
    CLI::App* cmd = app.add_subcommand(
        "capture",
        "Cut a plant seen by a depth source into single blades or leaves and fit each "
        "as an archetype: writes an archetype library");
    cmd->footer(R"(Examples:
  meadow capture samples/recordings/quadratic-leaf --out lib.json --glb lib.glb
  meadow capture tuft.oni --out lib.json --debug overlays/ --verbose
  meadow capture maize.oni --subject potted-plant --out lib.json --debug overlays/
  meadow capture pngs/ --intrinsics 525,525,319.5,239.5 --depth-unit 0.2mm --near 0.5 --far 1.1 --out lib.json

Record a dozen frames or more of a still plant, seen from the side with its base in view.
Reference: docs/cli.md (options), docs/capture.md (how it works, capturing your own plant).)");

    const char* input = "Input";
    cmd->add_option("SOURCE", args->source,
                    "Recording folder, folder of 16-bit PNGs, .oni file, or openni:// (camera)")
        ->required()
        ->group(input);
    addSourceOptions(*cmd, args->sourceArgs, input);
    cmd->add_option("--max-frames", args->options.maxFrames,
                    "Stop after this many frames (0 = all)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber)
        ->group(input);

    const char* frames = "Frames";
    cmd->add_option("--fuse", args->options.groups.fusionFrames,
                    "Frames fused per segmentation (1 = each frame alone)")
        ->capture_default_str()
        ->check(CLI::Range(1, 64))
        ->group(frames);
    cmd->add_option("--fusion", args->fusion,
                    "How fused frames become one: median or nearest-recurring")
        ->capture_default_str()
        ->check(CLI::IsMember(capture::kFusionMethodNames.names()))
        ->group(frames);
    cmd->add_option("--recurring-frames", args->options.groups.recurringFrames,
                    "Tips also follow readings that recur over this many frames (0 = off)")
        ->capture_default_str()
        ->check(CLI::Range(0, 64))
        ->group(frames);
    cmd->add_flag_callback(
           "--assume-still", [args] { args->options.groups.checkMotion = false; },
           "Take every run of frames for a still plant (no motion test)")
        ->group(frames);
    cmd->add_flag("--turntable", args->options.groups.turning,
                  "Every frame is a view of a turning plant: each segmented alone, the views "
                  "registered, each leaf kept once, pieces no other view shows left out")
        ->excludes("--assume-still")
        ->group(frames);

    const char* segmentation = "Segmentation";
    cmd->add_option("--near", args->options.segmenter.nearDepth_m,
                    "Near edge of the depth band, m (with --far; neither = automatic)")
        ->check(finiteRange(0.f, 20.f))
        ->group(segmentation);
    cmd->add_option("--far", args->options.segmenter.farDepth_m, "Far edge of the depth band, m")
        ->check(finiteRange(0.f, 20.f))
        ->group(segmentation);
    cmd->add_option("--subject", args->subject,
                    "What the camera looks at: tuft (blades from one base) or potted-plant "
                    "(leaves off a stem, in a room); picks --find-plant and --partition")
        ->capture_default_str()
        ->check(CLI::IsMember(capture::kSubjectNames.names()))
        ->group(segmentation);
    args->findPlantOption =
        cmd->add_option(
               "--find-plant", args->findPlant,
               "Without a band: clusters (room's planes off, the thin object in the middle) "
               "or depth-mode (nearest depth mode); default: the subject's")
            ->check(CLI::IsMember(capture::kPlantFindingNames.names()))
            ->group(segmentation);
    args->partitionOption =
        cmd->add_option(
               "--partition", args->partition,
               "Cut blades by: contour (a fan from one base) or stem-graph (leaves off a stem, "
               "followed through where they cross; the library then reports the stem's height); "
               "default: the subject's")
            ->check(CLI::IsMember(capture::kPartitionMethodNames.names()))
            ->group(segmentation);
    cmd->add_option("--plane", args->plane,
                    "Ground plane removal: " + capture::kPlaneMethodNames.list(", "))
        ->default_val(capture::toString(capture::SegmenterParams{}.planeMethod))
        ->check(CLI::IsMember(capture::kPlaneMethodNames.names()))
        ->group(segmentation);
    cmd->add_option("--edge-smoothing", args->options.segmenter.edgeSmoothingSigma_px,
                    "Sigma (contour points) smoothing the mask's edge (0 = off)")
        ->capture_default_str()
        ->check(finiteRange(0.f, 20.f))
        ->group(segmentation);
    cmd->add_flag("--keep-flagged", args->options.keepFlagged,
                  "Also model blades flagged overlapping, curling, too thin, ...")
        ->group(segmentation);

    const char* modelling = "Modeling";
    cmd->add_option("--knots", args->options.fit.refinedKnots,
                    "Skeleton knots the refiner keeps at most (0 = no refining)")
        ->capture_default_str()
        ->check(kRefinedKnotCount)
        ->group(modelling);
    cmd->add_option("--tolerance-mm", args->tolerance_mm,
                    "Keep the fewest width samples and knots within this error (0 = off)")
        ->default_val(0.f)
        ->check(finiteRange(0.f, 100.f))
        ->group(modelling);
    cmd->add_flag_callback(
           "--per-group", [args] { args->options.tracks.enabled = false; },
           "One archetype per blade and group, not one per blade (a moving camera)")
        ->group(modelling);
    cmd->add_option("--max-archetypes", args->options.maxArchetypes,
                    "Merge near-duplicates down to this many archetypes (0 = keep all)")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber)
        ->group(modelling);

    const char* output = "Output";
    cmd->add_option("--out", args->out, "Archetype library JSON to write")
        ->required()
        ->group(output);
    cmd->add_option("--glb", args->glb, "Also write the library as glTF 2.0 (.glb)")->group(output);
    cmd->add_option("--debug", args->debug, "Folder for an overlay PNG per segmentation")
        ->group(output);
    cmd->add_flag("--verbose", args->verbose, "List every skipped blade with its reason")
        ->group(output);
    cmd->callback([args] { runCapture(*args); });
}

}  // namespace meadow::cli
