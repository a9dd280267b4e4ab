// `meadow synth`: synthetic tufts with ground truth, rendered through the simulated sensor.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <string>

#include "commands.h"
#include "meadow/synth/error.h"
#include "meadow/synth/synthesize.h"
#include "option_checks.h"
#include "progress.h"

namespace meadow::cli {

namespace {

struct SynthArgs {
    synth::SynthOptions options;
    std::string out;
    bool list = false;
};

void runSynth(const SynthArgs& args) {
    if (args.list) {
        std::size_t width = 0;
        for (const auto& p : synth::synthPresets()) width = std::max(width, p.name.size());
        for (const auto& p : synth::synthPresets())
            std::cout << p.name << std::string(width + 2 - p.name.size(), ' ') << p.description
                      << '\n';
        return;
    }
    if (args.options.preset.empty() || args.out.empty())
        throw synth::SynthError(
            "synth needs --preset NAME and --out DIR (or --list to see the presets); known "
            "presets: " +
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
        "Render a synthetic tuft of known blades through the simulated depth sensor: a "
        "recording folder plus its ground truth");
    synth->footer(R"(Examples:
  meadow synth --list
  meadow synth --preset quadratic-leaf --out rec/
  meadow synth --preset wind --frames 30 --seed 7 --noise 0.5 --distance 1.0 --out rec/

Reference: docs/cli.md; the truth format: docs/formats.md.)");
    synth->add_option("--preset", args->options.preset,
                      "Tuft to render; `meadow synth --list` shows them");
    synth->add_option("--out", args->out,
                      "Recording folder to write (created; replaced if it is a meadow "
                      "recording)");
    synth->add_option("--frames", args->options.frames, "Frames to render")
        ->capture_default_str()
        ->check(CLI::Range(1, synth::kMaxSynthFrames));
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
                     "Camera distance to the tuft in metres (default: the preset's)")
        ->check(finiteRange(synth::kMinSynthDistance_m, synth::kMaxSynthDistance_m));
    synth
        ->add_option("--blades", args->options.bladeCount,
                     "Number of blades (default: the preset's)")
        ->check(CLI::Range(synth::kMinSynthBlades, synth::kMaxSynthBlades));
    synth->add_flag("--list", args->list, "List the presets, one a line, and exit");
    synth->callback([args]() { runSynth(*args); });
}

}  // namespace meadow::cli
