// Large meadows (issue 29): the bundled per-blade scene samples/scenes/meadow.json beside the
// tiled prairie samples/prairie/prairie.json (1 km x 1 km, tile instancing), at 640 x 360 on
// whatever driver EGL gets (Mesa llvmpipe without a GPU). Four runs, each N frames from frame 0
// in order (renderFrame, synchronous), the first two left out of the medians:
//   meadow              the per-blade scene as it is
//   prairie close-up    the prairie as it is (its camera path starts near the ground)
//   prairie horizon     the prairie with its camera held at the path's last key (high, far view)
//   prairie, no far field or shadows   the close-up without the far field's slices and shadows
// Each run happens in a child process of its own (fork), so its peak resident memory (VmHWM) is
// the run's alone. Writes large_meadow.md/.csv (frame and stage times, counts) and
// large_meadow_memory.md/.csv (GPU bytes, bytes per blade, peak resident memory) into --out.
// Run by tools/measure.sh (--only large).
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "common/report.h"
#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "meadow/runtime/scene.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth_px = 640, kHeight_px = 360;
constexpr int kWarmupFrames = 2;  // llvmpipe compiles the shaders on the first frames
// The bounds for the prairie.
constexpr double kGpuBound_bytes = 1e9;
constexpr double kProcessBound_bytes = 2e9;

enum class View { PathStart, PathEnd };

struct RunSpec {
    std::string name;  // row label, also the CSV's key
    fs::path scene;
    View view = View::PathStart;
    bool farFieldAndShadowsOff = false;
    bool tiled = false;
};

// What a child sends back through its pipe: plain numbers, so a raw copy of the struct will do.
struct RunResult {
    bool ok = false;
    char error[512] = {};
    char glRenderer[128] = {};
    int frames = 0;  // rendered, warm-up included
    double frame_ms = 0, prepass_ms = 0, physics_ms = 0, culling_ms = 0, shadows_ms = 0,
           draw_ms = 0, resolve_ms = 0;                    // medians after the warm-up
    double drawn = 0, tilesDrawn = 0, tilesSimulated = 0;  // medians after the warm-up
    double planted = 0;                                    // Renderer::bladeCount()
    double gpuBytes = 0;        // Renderer::gpuMemoryBytes() after the last frame
    double gpuBytesFrame0 = 0;  // ... after frame 0
    double drawnFrame0 = 0;
    double peakRss_MiB = 0;  // VmHWM after the last frame
};

void copyText(char* to, std::size_t size, const std::string& text) {
    std::snprintf(to, size, "%s", text.c_str());
}

// VmHWM of /proc/self/status in MiB; 0 when it cannot be read.
double peakResident_MiB() {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmHWM:", 0) == 0) {
            std::istringstream fields(line.substr(6));
            double kib = 0;
            fields >> kib;
            return kib / 1024.0;
        }
    return 0.0;
}

RunResult renderRun(const RunSpec& spec, int frames) {
    RunResult r;
    runtime::SceneDescription scene = runtime::loadSceneDescription(spec.scene);
    scene.render.width_px = kWidth_px;
    scene.render.height_px = kHeight_px;
    if (spec.view == View::PathEnd) scene.camera.path = {scene.camera.path.back()};
    if (spec.farFieldAndShadowsOff) {
        if (scene.tiling) scene.tiling->farField = false;
        scene.shadows.enabled = false;
    }
    runtime::GlContext context;
    copyText(r.glRenderer, sizeof r.glRenderer, context.renderer());
    runtime::Renderer renderer(context, scene);
    runtime::installPhysicsPass(renderer, context);
    runtime::installCullingPass(renderer, context);
    std::vector<double> frame, prepass, physics, culling, shadows, draw, resolve, drawn, tiles,
        simulated;
    for (int i = 0; i < frames; ++i) {
        std::cerr << "large meadow: " << spec.name << ", frame " << i + 1 << " of " << frames
                  << '\n';
        const runtime::FrameStats s = renderer.renderFrame(i).stats;
        if (i == 0) {
            r.gpuBytesFrame0 = static_cast<double>(renderer.gpuMemoryBytes());
            r.drawnFrame0 = static_cast<double>(s.bladesDrawn);
        }
        if (i < kWarmupFrames) continue;
        frame.push_back(s.frame_ms);
        prepass.push_back(s.gpuPrepass_ms);
        physics.push_back(s.gpuPhysics_ms);
        culling.push_back(s.gpuCulling_ms);
        shadows.push_back(s.gpuShadows_ms);
        draw.push_back(s.gpuDraw_ms);
        resolve.push_back(s.gpuResolve_ms);
        drawn.push_back(static_cast<double>(s.bladesDrawn));
        tiles.push_back(static_cast<double>(s.tilesDrawn));
        simulated.push_back(static_cast<double>(s.tilesSimulated));
    }
    r.frames = frames;
    r.frame_ms = median(frame);
    r.prepass_ms = median(prepass);
    r.physics_ms = median(physics);
    r.culling_ms = median(culling);
    r.shadows_ms = median(shadows);
    r.draw_ms = median(draw);
    r.resolve_ms = median(resolve);
    r.drawn = median(drawn);
    r.tilesDrawn = median(tiles);
    r.tilesSimulated = median(simulated);
    r.planted = static_cast<double>(renderer.bladeCount());
    r.gpuBytes = static_cast<double>(renderer.gpuMemoryBytes());
    r.peakRss_MiB = peakResident_MiB();
    r.ok = true;
    return r;
}

bool writeAll(int fd, const void* data, std::size_t size) {
    const auto* p = static_cast<const char*>(data);
    while (size > 0) {
        const ssize_t n = ::write(fd, p, size);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        p += n, size -= static_cast<std::size_t>(n);
    }
    return true;
}

// Runs `spec` in a child process (its own GL context, its own peak memory) and returns what it
// measured; a child that dies or fails comes back with ok false and the reason.
RunResult runInChild(const RunSpec& spec, int frames) {
    RunResult result;
    int fds[2];
    if (::pipe(fds) != 0) {
        copyText(result.error, sizeof result.error, "pipe() failed");
        return result;
    }
    std::cout.flush();
    std::cerr.flush();
    const pid_t pid = ::fork();
    if (pid < 0) {
        copyText(result.error, sizeof result.error, "fork() failed");
        return result;
    }
    if (pid == 0) {
        ::close(fds[0]);
        RunResult r;
        try {
            r = renderRun(spec, frames);
        } catch (const std::exception& e) {
            r = RunResult{};
            copyText(r.error, sizeof r.error, e.what());
        }
        std::cerr.flush();
        ::_exit(writeAll(fds[1], &r, sizeof r) ? 0 : 3);
    }
    ::close(fds[1]);
    std::size_t got = 0;
    auto* p = reinterpret_cast<char*>(&result);
    while (got < sizeof result) {
        const ssize_t n = ::read(fds[0], p + got, sizeof result - got);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        got += static_cast<std::size_t>(n);
    }
    ::close(fds[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (got != sizeof result) {
        result = RunResult{};
        const std::string why =
            WIFSIGNALED(status) ? "the child died of signal " + std::to_string(WTERMSIG(status))
                                : "the child exited with " + std::to_string(WEXITSTATUS(status));
        copyText(result.error, sizeof result.error, why + " before reporting");
    }
    return result;
}

std::string count(double value) { return fixed(value, 0); }
std::string mib(double bytes) { return fixed(bytes / (1024.0 * 1024.0), 1); }

int run(int argc, char** argv) {
    fs::path out = fs::path(MEADOW_SOURCE_DIR) / "docs/measurements";
    bool quick = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--quick")
            quick = true;
        else if (arg == "--out" && i + 1 < argc)
            out = argv[++i];
        else if (arg == "--made" && i + 1 < argc)
            setMadeLine(argv[++i]);
        else {
            std::cerr << "usage: meadow_prairie_bench [--quick] [--out DIR] [--made TEXT]\n";
            return 2;
        }
    }
    const int frames = quick ? 6 : 30;
    const fs::path source(MEADOW_SOURCE_DIR);
    const fs::path meadowScene = source / "samples/scenes/meadow.json";
    const fs::path prairieScene = source / "samples/prairie/prairie.json";
    const std::vector<RunSpec> specs{
        {"meadow (per-blade)", meadowScene, View::PathStart, false, false},
        {"prairie close-up", prairieScene, View::PathStart, false, true},
        {"prairie horizon (path's last key)", prairieScene, View::PathEnd, false, true},
        {"prairie close-up, no far field, no shadows", prairieScene, View::PathStart, true, true},
    };
    std::vector<RunResult> results;
    for (const RunSpec& spec : specs) {
        std::cerr << "large meadow: " << spec.name << " (" << spec.scene.string() << "), " << frames
                  << " frames in a child process\n";
        results.push_back(runInChild(spec, frames));
        if (!results.back().ok) {
            std::cerr << "prairie_bench: " << spec.name << ": " << results.back().error << '\n';
            return 1;
        }
    }
    fs::create_directories(out);
    const RunResult& meadow = results.front();
    const std::string glRenderer = meadow.glRenderer;
    const bool nvidia = glRenderer.find("NVIDIA") != std::string::npos;
    const std::string gpuNote = nvidia ? "" : " GPU (NVIDIA): not measured, no device was lent.";
    const int timed = frames - kWarmupFrames;

    // Frames: times and counts.
    std::ostringstream md, csv;
    md << "# Large meadows: the tiled prairie beside the per-blade meadow\n\n"
       << "`samples/scenes/meadow.json` (stored blades) and `samples/prairie/prairie.json` (1 km "
          "x 1 km terrain, tile instancing), each rendered at "
       << kWidth_px << "x" << kHeight_px << " with the scene's MSAA for " << frames
       << " frames in order from frame 0 (`Renderer::renderFrame`, synchronous, read-back "
          "included), physics and culling passes installed, one child process per row; medians "
          "of frames "
       << kWarmupFrames << "-" << frames - 1 << " (" << timed << "; the first " << kWarmupFrames
       << " compile shaders). Stage times are GPU timer queries; for the prairie, physics is "
          "the tile simulation and culling is making the near blades. Horizon: the camera held "
          "at the path's last key. Planted: `Renderer::bladeCount()`. x meadow: the row over "
          "the meadow row. Driver: "
       << glRenderer << "." << gpuNote << "\n\n"
       << "| Scene | Frame ms | x meadow | Prepass ms | Physics / tiles simulated ms | Culling / "
          "near blades made ms | Shadows ms | Draw ms | Resolve ms | Blades drawn | Blades "
          "planted | Planted x meadow | Tiles drawn | Tiles simulated |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    csv << "scene,frames,timed_frames,frame_ms,frame_ratio_to_meadow,prepass_ms,physics_ms,"
           "culling_ms,shadows_ms,draw_ms,resolve_ms,blades_drawn,blades_planted,"
           "planted_ratio_to_meadow,tiles_drawn,tiles_simulated\n";
    for (std::size_t k = 0; k < specs.size(); ++k) {
        const RunSpec& s = specs[k];
        const RunResult& r = results[k];
        const bool first = k == 0;
        const std::string frameRatio = first ? "" : fixed(r.frame_ms / meadow.frame_ms, 2);
        const std::string plantedRatio = first ? "" : fixed(r.planted / meadow.planted, 0);
        md << "| " << s.name << " | " << fixed(r.frame_ms, 1) << " | " << (first ? "1" : frameRatio)
           << " | " << fixed(r.prepass_ms, 2) << " | " << fixed(r.physics_ms, 2) << " | "
           << fixed(r.culling_ms, 2) << " | " << fixed(r.shadows_ms, 2) << " | "
           << fixed(r.draw_ms, 1) << " | " << fixed(r.resolve_ms, 2) << " | " << count(r.drawn)
           << " | " << count(r.planted) << " | " << (first ? "1" : plantedRatio) << " | "
           << (s.tiled ? count(r.tilesDrawn) : "-") << " | "
           << (s.tiled ? count(r.tilesSimulated) : "-") << " |\n";
        csv << '"' << s.name << "\"," << r.frames << ',' << timed << ',' << fixed(r.frame_ms, 3)
            << ',' << (first ? "1" : fixed(r.frame_ms / meadow.frame_ms, 4)) << ','
            << fixed(r.prepass_ms, 4) << ',' << fixed(r.physics_ms, 4) << ','
            << fixed(r.culling_ms, 4) << ',' << fixed(r.shadows_ms, 4) << ',' << fixed(r.draw_ms, 4)
            << ',' << fixed(r.resolve_ms, 4) << ',' << count(r.drawn) << ',' << count(r.planted)
            << ',' << (first ? "1" : fixed(r.planted / meadow.planted, 2)) << ','
            << (s.tiled ? count(r.tilesDrawn) : "") << ','
            << (s.tiled ? count(r.tilesSimulated) : "") << '\n';
    }
    if (!nvidia)
        md << "| GPU (NVIDIA) | not measured, no device was lent | | | | | | | | | | | | |\n";
    writeText(out / "large_meadow.md", md.str());
    writeText(out / "large_meadow.csv", csv.str());

    // Memory.
    std::ostringstream mmd, mcsv;
    mmd << "# Large meadows: memory\n\n"
        << "The runs of large_meadow.md. GPU: `Renderer::gpuMemoryBytes()` after the last frame "
           "(what meadow allocated: buffers, textures, render targets; not the driver's own). Per "
           "drawn blade: `gpuMemoryBytes()` / blades drawn, both at frame 0 of the run. Peak "
           "resident: VmHWM of /proc/self/status after the last frame, read in the run's own "
           "child process (fork() per row, before anything is loaded), so it covers that scene "
           "alone: loading, the GL context and "
        << frames
        << " frames. On llvmpipe the GPU's buffers live in the process, so peak "
           "resident includes them. Bounds of issue 29 for the prairie: GPU <= 1 GB, "
           "process <= 2 GB (10^9 bytes each). Driver: "
        << glRenderer << "." << gpuNote << "\n\n"
        << "| Scene | GPU MiB | Blades planted | GPU bytes / planted blade | Blades drawn (frame "
           "0) | GPU bytes / drawn blade | Peak resident MiB | Within bounds |\n"
        << "|---|---|---|---|---|---|---|---|\n";
    mcsv << "scene,gpu_bytes,blades_planted,gpu_bytes_per_planted_blade,blades_drawn_frame0,"
            "gpu_bytes_frame0,gpu_bytes_per_drawn_blade,peak_resident_mib,within_bounds\n";
    for (std::size_t k = 0; k < specs.size(); ++k) {
        const RunSpec& s = specs[k];
        const RunResult& r = results[k];
        const std::string perPlanted = r.planted > 0 ? fixed(r.gpuBytes / r.planted, 2) : "";
        const std::string perDrawn =
            r.drawnFrame0 > 0 ? fixed(r.gpuBytesFrame0 / r.drawnFrame0, 1) : "";
        const bool within =
            r.gpuBytes <= kGpuBound_bytes && r.peakRss_MiB * 1024.0 * 1024.0 <= kProcessBound_bytes;
        const std::string bounds = s.tiled ? (within ? "yes" : "**no**") : "-";
        mmd << "| " << s.name << " | " << mib(r.gpuBytes) << " | " << count(r.planted) << " | "
            << (perPlanted.empty() ? "-" : perPlanted) << " | " << count(r.drawnFrame0) << " | "
            << (perDrawn.empty() ? "-" : perDrawn) << " | " << fixed(r.peakRss_MiB, 0) << " | "
            << bounds << " |\n";
        mcsv << '"' << s.name << "\"," << count(r.gpuBytes) << ',' << count(r.planted) << ','
             << perPlanted << ',' << count(r.drawnFrame0) << ',' << count(r.gpuBytesFrame0) << ','
             << perDrawn << ',' << fixed(r.peakRss_MiB, 1) << ','
             << (s.tiled ? (within ? "yes" : "no") : "") << '\n';
    }
    if (!nvidia) mmd << "| GPU (NVIDIA) | not measured, no device was lent | | | | | | |\n";
    writeText(out / "large_meadow_memory.md", mmd.str());
    writeText(out / "large_meadow_memory.csv", mcsv.str());
    return 0;
}

}  // namespace
}  // namespace meadow::bench

int main(int argc, char** argv) {
    try {
        return meadow::bench::run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "prairie_bench: " << e.what() << '\n';
        return 1;
    }
}
