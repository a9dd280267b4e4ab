// `meadow synth`: synthetic tufts with ground truth, rendered through the simulated sensor.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "meadow/synth/error.h"
#include "meadow/synth/plant_synthesize.h"
#include "meadow/synth/synthesize.h"
#include "option_checks.h"
#include "progress.h"

namespace meadow::cli {

namespace {

struct SynthArgs {
    synth::SynthOptions options;
    std::string out;
    bool list = false;
    // A scanned plant instead of a preset.
    std::string plant, plantUnit = "mm", plantSkeleton, sensor = "kinect-v1";
    float plantVoxel_mm = 0.f;
    synth::PlantViewOptions views;
    bool noScenery = false;
    bool framesGiven = false;
};

void runPlant(const SynthArgs& args) {
    if (!args.options.preset.empty())
        throw synth::SynthError("synth takes --preset or --plant, not both");
    if (args.framesGiven)
        throw synth::SynthError(
            "--frames is for presets; a plant is rendered once per turntable view (--turntable N)");
    const auto unit = synth::kLengthUnitNames.parse(args.plantUnit);
    if (!unit)
        throw synth::SynthError("--plant-unit '" + args.plantUnit + "' is not one of " +
                                synth::kLengthUnitNames.list());
    synth::PlantSynthOptions options;
    options.plant = args.plant;
    options.scan.unit = *unit;
    options.scan.skeleton = args.plantSkeleton;
    options.scan.voxel_m = args.plantVoxel_mm * 1e-3f;
    options.views = args.views;
    if (args.options.distance_m > 0.f) options.views.distance_m = args.options.distance_m;
    options.views.scenery = !args.noScenery;
    options.views.seed = args.options.seed;
    options.sensor = args.sensor;
    options.noiseScale = args.options.noiseScale;
    options.seed = args.options.seed;
    options.out = args.out;
    Progress progress("synth " + options.plant.filename().string(),
                      static_cast<std::size_t>(options.views.views));
    const synth::PlantTruth truth = synth::synthesizePlant(
        options, [&progress](int done, int) { progress.update(static_cast<std::size_t>(done)); });
    progress.finish();
    int leaves = 0;
    for (const synth::PlantTruthOrgan& o : truth.views.front().organs) leaves += !o.stem;
    std::cout << "wrote " << truth.views.size() << " view(s) of '" << truth.plant << "' (" << leaves
              << " leaves and a stem; " << truth.stemFoundBy << ") to " << options.out.string()
              << " (truth in " << (options.out / "truth").string() << ")\n";
}

void runSynth(const SynthArgs& args) {
    if (args.list) {
        std::size_t width = 0;
        for (const auto& p : synth::synthPresets()) width = std::max(width, p.name.size());
        for (const auto& p : synth::synthPresets())
            std::cout << p.name << std::string(width + 2 - p.name.size(), ' ') << p.description
                      << '\n';
        return;
    }
    if (!args.plant.empty()) {
        if (args.out.empty()) throw synth::SynthError("synth --plant needs --out DIR");
        runPlant(args);
        return;
    }
    if (args.options.distance_m > 0.f && (args.options.distance_m < synth::kMinSynthDistance_m ||
                                          args.options.distance_m > synth::kMaxSynthDistance_m))
        throw synth::SynthError("--distance for a preset must be in [" +
                                std::to_string(synth::kMinSynthDistance_m).substr(0, 3) + ", " +
                                std::to_string(synth::kMaxSynthDistance_m).substr(0, 3) +
                                "] m, where its tuft fits the image");
    if (args.options.preset.empty() || args.out.empty())
        throw synth::SynthError(
            "synth needs --preset NAME or --plant FILE, and --out DIR (--list shows the "
            "presets); known presets: " +
            synth::synthPresetNames());
    if (!synth::findSynthPreset(args.options.preset))
        throw synth::SynthError("unknown preset '" + args.options.preset +
                                "'; known presets: " + synth::synthPresetNames());
    synth::SynthOptions options = args.options;
    options.out = args.out;
    Progress progress("synth " + options.preset, static_cast<std::size_t>(options.frames));
    synth::synthesize(
        options, [&progress](int done, int) { progress.update(static_cast<std::size_t>(done)); });
    progress.finish();
    std::cout << "wrote " << options.frames << " frame(s) of '" << options.preset << "' to "
              << options.out.string() << " (truth in " << (options.out / "truth").string() << ")\n";
}

}  // namespace

void addSynthCommand(CLI::App& app) {
    // The defaults shown are SynthOptions' own (capture_default_str), not copies of them.
    auto args = std::make_shared<SynthArgs>();
    CLI::App* synth = app.add_subcommand(
        "synth",
        "Render a synthetic tuft, or a real scanned plant, through a simulated depth sensor: a "
        "recording folder plus its ground truth");
    synth->footer(R"(Examples:
  meadow synth --list
  meadow synth --preset quadratic-leaf --out rec/
  meadow synth --preset wind --frames 30 --seed 7 --noise 0.5 --distance 1.0 --out rec/
  meadow synth --plant v-9-1-l-r.txt --turntable 12 --sensor kinect-v2 --out rec/

Reference: docs/cli.md; the truth formats: docs/formats.md.)");
    synth->add_option("--preset", args->options.preset,
                      "Tuft to render; `meadow synth --list` shows them");
    synth->add_option("--out", args->out,
                      "Recording folder to write (created; replaced if it is a meadow "
                      "recording)");
    synth->add_option("--frames", args->options.frames, "Frames to render (a preset)")
        ->capture_default_str()
        ->check(CLI::Range(1, synth::kMaxSynthFrames))
        ->each([args](const std::string&) { args->framesGiven = true; });
    synth
        ->add_option("--seed", args->options.seed,
                     "Random seed: the same seed gives the same files, byte for byte")
        ->capture_default_str()
        ->check(CLI::NonNegativeNumber);
    synth
        ->add_option("--noise", args->options.noiseScale,
                     "Sensor noise scale: 0 = exact depth (still quantised), 1 = a Kinect v1")
        ->capture_default_str()
        ->check(finiteRange(0.0, 10.0));
    synth
        ->add_option("--distance", args->options.distance_m,
                     "Camera distance in metres (default: the preset's; a plant: fits the image)")
        ->check(finiteRange(0.2, 10.0));
    synth
        ->add_option("--blades", args->options.bladeCount,
                     "Number of blades (default: the preset's)")
        ->check(CLI::Range(synth::kMinSynthBlades, synth::kMaxSynthBlades));
    synth->add_flag("--list", args->list, "List the presets, one a line, and exit");
    const char* plant = "Scanned plant";
    synth
        ->add_option("--plant", args->plant,
                     "Points with an organ label each: text \"x y z label\" or PLY")
        ->group(plant);
    synth->add_option("--plant-unit", args->plantUnit, "Its unit: mm, cm or m")
        ->capture_default_str()
        ->group(plant);
    synth
        ->add_option("--plant-skeleton", args->plantSkeleton,
                     "Skeleton graph (\"v x y z organ\", \"e i j\"); labels a PLY without them")
        ->group(plant);
    synth
        ->add_option("--plant-voxel-mm", args->plantVoxel_mm,
                     "Thin a dense scan to one point per cube of this side")
        ->check(finiteRange(0.0, 100.0))
        ->group(plant);
    synth
        ->add_option("--sensor", args->sensor,
                     "Simulated sensor: kinect-v1, kinect-v2 or realsense-d435")
        ->capture_default_str()
        ->check(CLI::IsMember(synth::plantSensorNames()))
        ->group(plant);
    synth->add_option("--turntable", args->views.views, "Views, 360/N degrees apart")
        ->capture_default_str()
        ->check(CLI::Range(1, 360))
        ->group(plant);
    synth->add_option("--pitch", args->views.pitch_deg, "Camera looks down by this (deg)")
        ->capture_default_str()
        ->check(finiteRange(-30.0, 89.0))
        ->group(plant);
    synth->add_option("--azimuth", args->views.azimuth_deg, "Plant turned by this in view 0 (deg)")
        ->check(finiteRange(-360.0, 360.0))
        ->group(plant);
    synth->add_flag("--no-scenery", args->noScenery, "No pot, floor, wall or clutter")
        ->group(plant);
    synth->callback([args]() { runSynth(*args); });
}

}  // namespace meadow::cli
