#include "meadow/runtime/frame_stats.h"

#include <cstdio>

namespace meadow::runtime {

std::string frameStatsCsvHeader() {
    return "frame,time_s,blades_total,blades_drawn,culled_orientation,culled_frustum,culled_"
           "distance,culled_occlusion,tiles_drawn,tiles_simulated,gpu_prepass_ms,gpu_physics_ms,"
           "gpu_culling_ms,gpu_shadows_ms,gpu_draw_ms,gpu_resolve_ms,frame_ms\n";
}

std::string toCsvRow(const FrameStats& s) {
    char row[512];
    std::snprintf(
        row, sizeof row,
        "%d,%.4f,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f\n",
        s.frame, s.time_s, static_cast<unsigned long long>(s.bladesTotal),
        static_cast<unsigned long long>(s.bladesDrawn),
        static_cast<unsigned long long>(s.culledOrientation),
        static_cast<unsigned long long>(s.culledFrustum),
        static_cast<unsigned long long>(s.culledDistance),
        static_cast<unsigned long long>(s.culledOcclusion),
        static_cast<unsigned long long>(s.tilesDrawn),
        static_cast<unsigned long long>(s.tilesSimulated), s.gpuPrepass_ms, s.gpuPhysics_ms,
        s.gpuCulling_ms, s.gpuShadows_ms, s.gpuDraw_ms, s.gpuResolve_ms, s.frame_ms);
    return row;
}

}  // namespace meadow::runtime
