// Fills the pool slots of tiles that start to be simulated with their blades as they stand now
// (settledBlade), so a tile's blades do not jump when it starts or stops being simulated.
// One invocation per blade of the tiles in the list.
// Prepended: shared/blade_types.h, shared/physics_params.h, shared/tiling_types.h,
// common_dispatch.glsl, common_physics.glsl, common_tiles.glsl.
layout(local_size_x = BLADE_WORKGROUP_SIZE) in;

layout(std140, binding = PHYSICS_UBO_BINDING) uniform PhysicsBlock { PhysicsParamsGpu physics; };
layout(std140, binding = TILING_UBO_BINDING) uniform TilingBlock { TilingParamsGpu tiling; };
layout(std430, binding = TILE_INSTANCE_SSBO_BINDING) restrict readonly buffer Instances {
    TileInstanceGpu instances[];
};
layout(std430, binding = TILE_DRAW_SSBO_BINDING) restrict readonly buffer Tiles { TileDrawGpu tiles[]; };
layout(std430, binding = TILE_POOL_BLADE_SSBO_BINDING) restrict writeonly buffer PoolBlades {
    BladeGpu poolBlades[];
};
layout(std430, binding = TILE_POOL_REST_SSBO_BINDING) restrict writeonly buffer PoolRests {
    BladeRestGpu poolRests[];
};

void main() {
    uint i = flatInvocation();
    uint patchBlades = tiling.counts.y;
    if (i >= tiling.counts.x * patchBlades) return;
    TileDrawGpu t = tiles[i / patchBlades];
    uint k = i % patchBlades;
    TileBlade b = tileRestBlade(t.tile.xy, instances[k], tiling);
    uint at = t.tile.z * patchBlades + k;
    poolBlades[at] = settledBlade(b, physics);
    poolRests[at] = b.rest;
}
