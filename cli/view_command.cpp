// `meadow view SCENE`: a window to fly through a meadow, drawn by the same passes as
// `meadow render`. Keys and options: docs/cli.md, "meadow view".
#include <GLFW/glfw3.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "commands.h"
#include "fly_camera.h"
#include "meadow/core/atomic_file.h"
#include "meadow/runtime/culling.h"
#include "meadow/runtime/error.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "output_checks.h"
#include "scene_options.h"
#include "view_window.h"

namespace meadow::cli {
namespace {

namespace fs = std::filesystem;

constexpr float kFlySpeed_mps = 1.5f;     // a brisk walk through a meadow a few metres across
constexpr float kFastFactor = 5.f;        // with Shift held
constexpr float kTurn_radPerPx = 0.003f;  // a drag across a 1280 px window turns about 220 degrees
// Wall-clock steps longer than this (a stall, a window drag) advance the simulation by this
// much only, so the blades do not jump.
constexpr double kMaxWallStep_s = 0.1;
constexpr double kTitleInterval_s = 0.5;  // how often the title's frame time is refreshed

struct ViewArgs {
    std::string scene;
    std::string library;     // archetype library replacing the scene's archetypes, empty = keep
    std::string size;        // "WxH", empty = the scene's
    std::string screenshot;  // PNG of the last of --frames frames, empty = none
    int frames = 0;          // 0: until the window is closed
    bool fixedStep = false;  // 1 / render.frame_rate_hz of simulated time per frame
};

// What the toggle keys have set.
struct ViewToggles {
    bool paused = false;
    bool culling = true;
    bool wireframe = false;
};

bool isPngFile(const fs::path& path) {
    constexpr char kSignature[8] = {'\x89', 'P', 'N', 'G', '\r', '\n', '\x1a', '\n'};
    char head[8] = {};
    std::ifstream in(path, std::ios::binary);
    return in.read(head, sizeof head) && std::equal(head, head + 8, kSignature);
}

void checkScreenshotPath(const std::string& path) {
    std::string extension = fs::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (extension != ".png")
        throw runtime::RuntimeError("view: --screenshot '" + path +
                                    "' must name a .png file (e.g. shot.png)");
    refuseToReplace(path, "--screenshot", isPngFile, "it is not a PNG image");
    checkWritable(path);
}

void writePng(const fs::path& path, const cv::Mat& image_bgr) {
    std::vector<unsigned char> png;
    if (!cv::imencode(".png", image_bgr, png))
        throw runtime::RuntimeError("view: PNG encoding of " + path.string() + " failed");
    writeFileAtomically(path,
                        std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
}

// meadow_view_001.png, _002, ...: the first name in the working folder not taken yet.
fs::path freeScreenshotName() {
    for (int i = 1;; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "meadow_view_%03d.png", i);
        if (!fs::exists(name)) return name;
    }
}

// WASD along the view, E / Q up and down: x right, y up, z forward.
glm::vec3 heldMove(const ViewWindow& window) {
    auto axis = [&](int plus, int minus) {
        return (window.isKeyDown(plus) ? 1.f : 0.f) - (window.isKeyDown(minus) ? 1.f : 0.f);
    };
    return {axis(GLFW_KEY_D, GLFW_KEY_A), axis(GLFW_KEY_E, GLFW_KEY_Q),
            axis(GLFW_KEY_W, GLFW_KEY_S)};
}

// Acts on the keys pressed since the last frame; true when F12 asked for a screenshot.
bool applyKeys(ViewWindow& window, runtime::Renderer& renderer, ViewToggles& toggles) {
    bool screenshotWanted = false;
    for (int key : window.takePressedKeys()) {
        switch (key) {
            case GLFW_KEY_ESCAPE:
                window.requestClose();
                break;
            case GLFW_KEY_P:
            case GLFW_KEY_SPACE:
                toggles.paused = !toggles.paused;
                break;
            case GLFW_KEY_C:
                toggles.culling = !toggles.culling;
                renderer.setCullingEnabled(toggles.culling);
                break;
            case GLFW_KEY_F:
                toggles.wireframe = !toggles.wireframe;
                renderer.setWireframe(toggles.wireframe);
                break;
            case GLFW_KEY_F12:
                screenshotWanted = true;
                break;
            default:
                break;
        }
    }
    return screenshotWanted;
}

std::string titleOf(double frame_ms, std::uint64_t bladesDrawn, const ViewToggles& toggles) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "meadow view \u2014 %.1f ms (%.0f fps), %llu blades drawn%s%s%s", frame_ms,
                  frame_ms > 0.0 ? 1000.0 / frame_ms : 0.0,
                  static_cast<unsigned long long>(bladesDrawn), toggles.paused ? ", paused" : "",
                  toggles.culling ? "" : ", culling off", toggles.wireframe ? ", wireframe" : "");
    return text;
}

void runView(const ViewArgs& args) {
    using Clock = std::chrono::steady_clock;
    const runtime::SceneDescription scene =
        loadSceneWithOptions("view", args.scene, args.library, args.size);
    if (!args.screenshot.empty()) checkScreenshotPath(args.screenshot);

    // Destroyed in reverse: the renderer's GL objects, then the adopted context, then the window
    // that owns it.
    const runtime::GlContextOptions contextOptions;
    ViewWindow window(scene.render.width_px, scene.render.height_px, contextOptions.debugOutput);
    runtime::GlContext context = runtime::GlContext::adoptCurrent(contextOptions);
    runtime::Renderer renderer(context, scene);
    runtime::installPhysicsPass(renderer, context);
    runtime::installCullingPass(renderer, context);
    std::cerr << "meadow view: " << renderer.summary() << " on " << context.renderer() << '\n';

    const bool scripted = args.frames > 0;
    window.setSwapInterval(scripted ? 0 : 1);  // a scripted run waits for no display refresh
    const runtime::CameraKey& start = scene.camera.path.front();
    FlyCamera camera = FlyCamera::lookingAt(start.position_m, start.target_m);
    ViewToggles toggles;
    const float fixedStep_s = 1.f / scene.render.frameRate_hz;
    float time_s = 0.f;
    auto last = Clock::now();
    const auto begin = last;
    auto titleShown = last;
    int framesSinceTitle = 0, frame = 0;
    for (; !window.closeRequested() && (!scripted || frame < args.frames); ++frame) {
        const auto now = Clock::now();
        const double wallStep_s = std::chrono::duration<double>(now - last).count();
        last = now;
        const bool screenshotWanted = applyKeys(window, renderer, toggles);
        const bool fast =
            window.isKeyDown(GLFW_KEY_LEFT_SHIFT) || window.isKeyDown(GLFW_KEY_RIGHT_SHIFT);
        camera.look(window.takeLookDelta_px(), kTurn_radPerPx);
        camera.move(heldMove(window),
                    kFlySpeed_mps * (fast ? kFastFactor : 1.f) * static_cast<float>(wallStep_s));

        // Frame 0 is the rest pose, as in meadow render.
        float step_s = 0.f;
        if (frame > 0 && !toggles.paused)
            step_s = args.fixedStep ? fixedStep_s
                                    : static_cast<float>(std::min(wallStep_s, kMaxWallStep_s));
        time_s += step_s;
        const bool lastFrame = scripted && frame == args.frames - 1;
        const bool titleDue =
            std::chrono::duration<double>(now - titleShown).count() >= kTitleInterval_s;
        runtime::ViewFrame view;
        view.camera = {camera.position_m(), camera.target_m()};
        view.time_s = time_s;
        view.deltaTime_s = step_s;
        view.wantStats = titleDue;
        view.wantImage = screenshotWanted || (lastFrame && !args.screenshot.empty());
        const runtime::RenderedFrame rendered = renderer.renderView(view);
        const glm::ivec2 windowSize_px = window.framebufferSize_px();
        renderer.blitToDefaultFramebuffer(windowSize_px.x, windowSize_px.y);
        if (screenshotWanted) {
            const fs::path name = freeScreenshotName();
            writePng(name, rendered.image_bgr);
            std::cout << "meadow view: saved " << name.string() << '\n';
        }
        if (lastFrame && !args.screenshot.empty()) writePng(args.screenshot, rendered.image_bgr);
        if (titleDue) {
            // The frames begun since the last title, up to this one's start.
            const double mean_ms =
                std::chrono::duration<double, std::milli>(now - titleShown).count() /
                std::max(framesSinceTitle, 1);
            window.setTitle(titleOf(mean_ms, rendered.stats.bladesDrawn, toggles));
            titleShown = now;
            framesSinceTitle = 0;
        }
        ++framesSinceTitle;
        window.present();
    }
    if (!scripted) return;
    if (frame < args.frames)
        throw runtime::RuntimeError("view: the window was closed after " + std::to_string(frame) +
                                    " of " + std::to_string(args.frames) + " frames" +
                                    (args.screenshot.empty() ? "" : "; no screenshot written"));
    const double mean_ms =
        std::chrono::duration<double, std::milli>(Clock::now() - begin).count() / frame;
    std::cout << "viewed " << frame << " frame(s) of " << renderer.bladeCount()
              << " blades (mean frame time " << mean_ms << " ms)";
    if (!args.screenshot.empty()) std::cout << "; wrote " << args.screenshot;
    std::cout << '\n';
}

}  // namespace

void addViewCommand(CLI::App& app) {
    auto args = std::make_shared<ViewArgs>();
    CLI::App* view = app.add_subcommand(
        "view", "Fly through a scene in a window, drawn like meadow render draws it");
    view->footer(R"(Keys: WASD fly, Q/E down/up, hold a mouse button to look, Shift faster,
  P or Space pause, C culling, F wireframe, F12 screenshot, Esc quit.

Examples:
  meadow view samples/scenes/meadow.json
  meadow view samples/scenes/meadow.json --library lib.json --size 1280x720
  xvfb-run -a meadow view samples/scenes/meadow.json --frames 20 --fixed-step --screenshot shot.png

Needs a display (DISPLAY); for headless frames use meadow render. Reference: docs/cli.md.)");
    const char* input = "Input";
    view->add_option("SCENE", args->scene, "Scene file")->required()->group(input);
    view->add_option("--library", args->library,
                     "Archetype library to plant instead of the scene's archetypes")
        ->group(input);
    const char* window = "Window";
    view->add_option("--size", args->size, "Window size WIDTHxHEIGHT (default: the scene's)")
        ->group(window);
    const char* scripted = "Scripted runs";
    CLI::Option* frames = view->add_option("--frames", args->frames, "Render N frames, then exit")
                              ->check(CLI::Range(1, 1000000))
                              ->group(scripted);
    view->add_option("--screenshot", args->screenshot, "Write the last frame to FILE.png")
        ->needs(frames)
        ->group(scripted);
    view->add_flag("--fixed-step", args->fixedStep,
                   "Advance 1 / render.frame_rate_hz of simulated time per frame")
        ->group(scripted);
    view->callback([args] { runView(*args); });
}

}  // namespace meadow::cli
