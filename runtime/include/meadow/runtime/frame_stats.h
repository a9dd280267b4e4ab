#pragma once
// What one rendered frame cost and drew; one CSV row per frame.
#include <cstdint>
#include <string>

namespace meadow::runtime {

struct FrameStats {
    int frame = 0;
    double time_s = 0.0;  // simulated time of the frame
    std::uint64_t bladesTotal = 0;
    std::uint64_t bladesDrawn = 0;
    std::uint64_t culledOrientation = 0;
    std::uint64_t culledFrustum = 0;
    std::uint64_t culledDistance = 0;
    std::uint64_t culledOcclusion = 0;  // a tiled scene counts blades thinned out as distance
    // A tiled scene: tiles whose blades were made this frame, tiles simulated.
    std::uint64_t tilesDrawn = 0;
    std::uint64_t tilesSimulated = 0;
    // GPU time of each stage (GL_TIME_ELAPSED queries), milliseconds; 0 for a stage not run.
    double gpuPrepass_ms = 0.0;
    double gpuPhysics_ms = 0.0;
    double gpuCulling_ms = 0.0;  // a tiled scene: making its near blades
    double gpuShadows_ms = 0.0;
    double gpuDraw_ms = 0.0;
    double gpuResolve_ms = 0.0;
    double frame_ms = 0.0;  // CPU wall time of the whole frame, read-back included
};

std::string frameStatsCsvHeader();  // with trailing newline
std::string toCsvRow(const FrameStats& stats);

}  // namespace meadow::runtime
