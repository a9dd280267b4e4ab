#pragma once
// The far field of a tiled scene (Habel et al. 2007, ray-traced grass slices; Boulanger et al.,
// volume slices): the tile patch's blades drawn side-on into vertical slices, one per slab of
// the tile along x and along z, which the terrain's fragment shader traces where the blades have
// thinned out. Built on the CPU from the same patch and archetypes the near blades come from.
#include <array>
#include <glm/vec3.hpp>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "meadow/runtime/scene.h"
#include "shared/tiling_types.h"

namespace meadow::runtime {

struct FarFieldSlices {
    // CV_8UC4 (R, G, B gamma-encoded albedo; A coverage), row 0 at the ground; layers
    // [0, perAxis) are the slabs across z (planes of constant z, u along x), the next perAxis
    // across x (u along z).
    std::vector<cv::Mat> layers;
    int perAxis = 0;
    float spacing_m = 0.f;   // distance between neighbouring slice planes: tile size / perAxis
    float height_m = 0.f;    // the slices' top: the highest point a blade reaches
    float tileSize_m = 0.f;  // the slices repeat along u with the tile
    // Averages over every layer, per band of height (band 0 at the ground): the share a slice
    // covers, and the linear albedo of what it covers. Far away the slices are drawn as these
    // averages (terrain.frag): a grazing ray sees the tips' band first, a steep one every band.
    static constexpr int kHeightBands = 8;
    std::array<float, kHeightBands> bandCoverage{};
    std::array<glm::vec3, kHeightBands> bandAlbedo{};
};

// width_px texels along a tile, height_px up to the tallest blade; perAxis slabs a direction.
FarFieldSlices buildFarFieldSlices(const std::vector<gpu::TileInstanceGpu>& patch,
                                   const SceneDescription& scene, int perAxis = 16,
                                   int width_px = 512, int height_px = 64);

}  // namespace meadow::runtime
