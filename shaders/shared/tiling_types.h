// Buffer layouts and bindings of tile instancing (runtime/src/tiled_field.h), shared by the
// tile shaders and the C++ runtime. Compiles as GLSL 4.50 and as C++20; vec4 / uvec4 only.
#ifdef __cplusplus
#pragma once
#include <cstddef>

#include "blade_types.h"
namespace meadow::runtime::gpu {
#endif

#define TILE_INSTANCE_SSBO_BINDING 9
#define TILE_DRAW_SSBO_BINDING 10
#define TILE_POOL_BLADE_SSBO_BINDING 11
#define TILE_POOL_REST_SSBO_BINDING 12
#define TILING_UBO_BINDING 3
#define TERRAIN_HEIGHT_TEXTURE_UNIT 1
#define TERRAIN_DENSITY_TEXTURE_UNIT 2

// A tile that is not simulated (TileDrawGpu.tile.z).
#define TILE_NOT_SIMULATED 0xffffffffu

// One blade of the patch every tile draws: where it stands in the tile and its rest shape in its
// own frame (front d, up n, width w of seeding.cpp's restPose), so a tile on a slope or turned
// about up places it with its own frame.
struct TileInstanceGpu {
    vec4 place;          // x, z from the tile's min corner (m), w direction angle (rad)
    vec4 restV1_width;   // v1 - v0 along (d, n, w) (m), w blade width (m)
    vec4 restV2_height;  // v2 - v0 along (d, n, w) (m), w blade height (m)
    vec4 look;           // x archetype, y stiffness s, z density threshold in [0, 1), w unused
};

// One tile drawn this frame.
struct TileDrawGpu {
    uvec4 tile;  // x column, y row (from the terrain's min corner), z pool slot or
                 // TILE_NOT_SIMULATED, w unused
};

struct TilingParamsGpu {
    vec4 tile;     // x tile size (m), y near distance (m), z transition band (m), w distance from
                   // which the blades thin (m)
    vec4 terrain;  // xy terrain min XZ (m), zw its size (m)
    uvec4 counts;  // x tiles drawn, y patch blades, z most blades drawn, w 1 = per-blade culling
    vec4 unused;
};

#ifdef __cplusplus
static_assert(sizeof(TileInstanceGpu) == 64 && sizeof(TileDrawGpu) == 16);
static_assert(sizeof(TilingParamsGpu) == 64);
}  // namespace meadow::runtime::gpu
#endif
