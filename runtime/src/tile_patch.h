#pragma once
// The patch every tile of a tiled scene draws (Fan & Sheng, Sec. 4.5): the scene's blade
// seeding (density, tufts, archetypes, scales, stiffness) run once on one flat tile, each blade
// stored in its own frame with a density threshold (Boulanger et al.) for thinning at run time.
#include <vector>

#include "meadow/runtime/scene.h"
#include "shared/tiling_types.h"

namespace meadow::runtime {

// Deterministic for the scene's seed; a multiple of BLADE_WORKGROUP_SIZE blades. Throws
// RuntimeError when the tile would hold no blade.
std::vector<gpu::TileInstanceGpu> buildTilePatch(const SceneDescription& scene);

// The tallest blade of the patch (m): how far above the terrain a tile's box must reach.
float tallestBlade_m(const std::vector<gpu::TileInstanceGpu>& patch);

}  // namespace meadow::runtime
