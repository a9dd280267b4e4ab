// `meadow render SCENE --out DIR`: PNG frames of a scene plus per-frame statistics (CSV).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "commands.h"
#include "meadow/core/atomic_file.h"
#include "meadow/core/staged_folder.h"
#include "meadow/modeling/archetype_library.h"
#include "meadow/runtime/culling.h"
#include "meadow/runtime/error.h"
#include "meadow/runtime/frame_stats.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "meadow/runtime/scene.h"
#include "output_checks.h"
#include "progress.h"

namespace meadow::cli {
namespace {

constexpr const char* kStatsFileName = "stats.csv";

// What a render's output folder holds: frame_NNNNN.png and stats.csv.
bool isRenderOutputName(const std::string& name) {
    constexpr std::string_view kPrefix = "frame_", kSuffix = ".png";
    const bool frame =
        name.size() > kPrefix.size() + kSuffix.size() && name.starts_with(kPrefix) &&
        name.ends_with(kSuffix) &&
        name.find_first_not_of("0123456789", kPrefix.size()) == name.size() - kSuffix.size();
    return frame || name == kStatsFileName;
}

struct RenderArgs {
    std::string scene;
    std::string out;
    int frames = 1;
    std::string size;     // "WxH", empty = the scene's
    std::string library;  // archetype library replacing the scene's archetypes, empty = keep
};

void runRender(const RenderArgs& args) {
    namespace fs = std::filesystem;
    runtime::SceneDescription scene = runtime::loadSceneDescription(args.scene);
    if (!args.library.empty()) {
        // A captured library replaces the scene's archetypes; each archetype is equally likely,
        // since the scene's weights name the archetypes it was written for.
        scene.archetypes = modeling::loadArchetypeLibrary(args.library).archetypes;
        scene.archetypeWeights.assign(scene.archetypes.size(), 1.f);
    }
    if (!args.size.empty()) {
        int w = 0, h = 0;
        char x = 0, extra = 0;
        if (std::sscanf(args.size.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 ||
            (x != 'x' && x != 'X') || w < 1 || h < 1 || w > 16384 || h > 16384)
            throw runtime::RuntimeError("render: --size '" + args.size +
                                        "' is not WIDTHxHEIGHT in pixels (e.g. 1280x720)");
        scene.render.width_px = w;
        scene.render.height_px = h;
    }
    // The output folder is one unit: frames and statistics are written beside it and replace a
    // previous render whole, so no old frame outlives a new stats.csv.
    refuseFolderOfOthers(args.out, "--out", isRenderOutputName,
                         "it holds files that are not a render's frames and statistics");
    StagedFolder staged(args.out);

    runtime::GlContext context;
    runtime::Renderer renderer(context, scene);
    runtime::installPhysicsPass(renderer, context);
    runtime::installCullingPass(renderer, context);
    std::cerr << "meadow render: " << renderer.bladeCount() << " blades in "
              << renderer.patchCount() << " patches on " << context.renderer() << '\n';

    std::string csv = runtime::frameStatsCsvHeader();
    Progress progress("render", static_cast<std::size_t>(args.frames));
    double totalFrame_ms = 0.0;
    // Pipelined: frame i is written while the GPU renders the frames after it.
    renderer.renderFrames(0, args.frames, /*wantImages=*/true, [&](runtime::RenderedFrame&& frame) {
        const int i = frame.stats.frame;
        std::vector<unsigned char> png;
        if (!cv::imencode(".png", frame.image_bgr, png))
            throw runtime::RuntimeError("render: PNG encoding of frame " + std::to_string(i) +
                                        " failed");
        char name[32];
        std::snprintf(name, sizeof name, "frame_%05d.png", i);
        writeFileAtomically(
            staged.path() / name,
            std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
        csv += runtime::toCsvRow(frame.stats);
        totalFrame_ms += frame.stats.frame_ms;
        progress.update(static_cast<std::size_t>(i + 1));
    });
    progress.finish();
    writeFileAtomically(staged.path() / kStatsFileName, csv);
    staged.commit();
    std::cout << "wrote " << args.frames << " frame(s) of " << renderer.bladeCount()
              << " blades to " << args.out << " (mean frame time " << totalFrame_ms / args.frames
              << " ms; stats.csv)\n";
}

}  // namespace

void addRenderCommand(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* render = app.add_subcommand(
        "render", "Render a scene (meadow.scene JSON) to PNG frames and per-frame statistics");
    render->footer(R"(Examples:
  meadow render samples/scenes/meadow.json --out frames/ --frames 90
  meadow render samples/scenes/meadow.json --library lib.json --out frames/ --size 1280x720

Reference: docs/cli.md, docs/rendering.md; the scene format: docs/formats.md, "Scene".)");
    const char* input = "Input";
    render->add_option("SCENE", args->scene, "Scene file")->required()->group(input);
    render
        ->add_option("--library", args->library,
                     "Archetype library to plant instead of the scene's archetypes")
        ->group(input);
    const char* output = "Output";
    render->add_option("--out", args->out, "Folder for frame_NNNNN.png and stats.csv")
        ->required()
        ->group(output);
    render
        ->add_option("--frames", args->frames,
                     "Frames to render, 1 / render.frame_rate_hz apart in time")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000000))
        ->group(output);
    render->add_option("--size", args->size, "Image size WIDTHxHEIGHT (default: the scene's)")
        ->group(output);
    render->callback([args] { runRender(*args); });
}

}  // namespace meadow::cli
