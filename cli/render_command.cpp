// `meadow render SCENE --out DIR`: PNG frames of a scene plus per-frame statistics (CSV);
// `--video FILE.mp4`: the same frames as a video.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>

#include "commands.h"
#include "meadow/core/atomic_file.h"
#include "meadow/core/staged_folder.h"
#include "meadow/runtime/culling.h"
#include "meadow/runtime/error.h"
#include "meadow/runtime/frame_stats.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "meadow/runtime/scene.h"
#include "output_checks.h"
#include "progress.h"
#include "scene_options.h"
#include "video_writer.h"

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
    std::string video;
    int frames = 1;
    std::string size;     // "WxH", empty = the scene's
    std::string library;  // archetype library replacing the scene's archetypes, empty = keep
};

void writeFramePng(const std::filesystem::path& folder, int i, const cv::Mat& bgr) {
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", bgr, png))
        throw runtime::RuntimeError("render: PNG encoding of frame " + std::to_string(i) +
                                    " failed");
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.png", i);
    writeFileAtomically(folder / name,
                        std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

void runRender(const RenderArgs& args) {
    if (args.out.empty() && args.video.empty())
        throw runtime::RuntimeError(
            "render: give --out FOLDER for PNG frames, --video FILE.mp4, or both");
    runtime::SceneDescription scene =
        loadSceneWithOptions("render", args.scene, args.library, args.size);
    // The output folder is one unit: frames and statistics are written beside it and replace a
    // previous render whole, so no old frame outlives a new stats.csv.
    std::optional<StagedFolder> staged;
    if (!args.out.empty()) {
        refuseFolderOfOthers(args.out, "--out", isRenderOutputName,
                             "it holds files that are not a render's frames and statistics");
        staged.emplace(args.out);
    }
    std::optional<VideoWriter> video;
    if (!args.video.empty())
        video.emplace(args.video, scene.render.width_px, scene.render.height_px,
                      scene.render.frameRate_hz);

    runtime::GlContext context;
    runtime::Renderer renderer(context, scene);
    runtime::installPhysicsPass(renderer, context);
    runtime::installCullingPass(renderer, context);
    std::cerr << "meadow render: " << renderer.summary() << " on " << context.renderer() << '\n';

    std::string csv = runtime::frameStatsCsvHeader();
    Progress progress("render", static_cast<std::size_t>(args.frames));
    double totalFrame_ms = 0.0;
    // Pipelined: frame i is written while the GPU renders the frames after it.
    renderer.renderFrames(0, args.frames, /*wantImages=*/true, [&](runtime::RenderedFrame&& frame) {
        const int i = frame.stats.frame;
        if (staged) writeFramePng(staged->path(), i, frame.image_bgr);
        if (video) video->write(frame.image_bgr);
        csv += runtime::toCsvRow(frame.stats);
        totalFrame_ms += frame.stats.frame_ms;
        progress.update(static_cast<std::size_t>(i + 1));
    });
    progress.finish();
    if (video) video->finish();
    if (staged) {
        writeFileAtomically(staged->path() / kStatsFileName, csv);
        staged->commit();
    }
    std::cout << "wrote " << args.frames << " frame(s) of " << renderer.bladeCount()
              << " blades (mean frame time " << totalFrame_ms / args.frames << " ms)";
    if (staged) std::cout << " to " << args.out << " (PNG frames, stats.csv)";
    if (video) std::cout << (staged ? " and " : " to ") << args.video << " (video)";
    std::cout << '\n';
}

}  // namespace

void addRenderCommand(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* render = app.add_subcommand(
        "render", "Render a scene (meadow.scene JSON) to PNG frames and statistics, or a video");
    render->footer(R"(Examples:
  meadow render samples/scenes/meadow.json --out frames/ --frames 90
  meadow render samples/scenes/meadow.json --library lib.json --out frames/ --size 1280x720
  meadow render samples/scenes/meadow.json --video meadow.mp4 --frames 150

Reference: docs/cli.md, docs/rendering.md; the scene format: docs/formats.md, "Scene".)");
    const char* input = "Input";
    render->add_option("SCENE", args->scene, "Scene file")->required()->group(input);
    render
        ->add_option("--library", args->library,
                     "Archetype library to plant instead of the scene's archetypes")
        ->group(input);
    const char* output = "Output";
    render->add_option("--out", args->out, "Folder for frame_NNNNN.png and stats.csv")
        ->group(output);
    render
        ->add_option("--video", args->video,
                     "MP4 video of the frames (H.264, through ffmpeg), with or without --out")
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
