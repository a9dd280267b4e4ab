// The near field of a tiled scene (Fan & Sheng, Sec. 4.5): every blade of every tile drawn this
// frame is made from the shared patch, thinned by the density map and with distance by its
// threshold (Boulanger et al.), culled like a stored blade (orientation, frustum, occlusion;
// Jahrmann & Wimmer 2017, Sec. 5.2), and appended to the draw buffers the blade draw reads.
// Simulated tiles take the pose from their pool slot; the others settle under this instant's
// wind (settledBlade). One workgroup per tile and BLADE_WORKGROUP_SIZE patch blades.
// Prepended: shared/blade_types.h, shared/physics_params.h, shared/cull_params.h,
// shared/tiling_types.h, common_dispatch.glsl, common_physics.glsl, common_culling.glsl,
// common_culling_depth.glsl, common_tiles.glsl.
layout(local_size_x = BLADE_WORKGROUP_SIZE) in;

layout(std140, binding = PHYSICS_UBO_BINDING) uniform PhysicsBlock { PhysicsParamsGpu physics; };
layout(std140, binding = CULL_UBO_BINDING) uniform CullBlock { CullParamsGpu cull; };
layout(std140, binding = TILING_UBO_BINDING) uniform TilingBlock { TilingParamsGpu tiling; };
layout(std430, binding = TILE_INSTANCE_SSBO_BINDING) restrict readonly buffer Instances {
    TileInstanceGpu instances[];
};
layout(std430, binding = TILE_DRAW_SSBO_BINDING) restrict readonly buffer Tiles { TileDrawGpu tiles[]; };
layout(std430, binding = TILE_POOL_BLADE_SSBO_BINDING) restrict readonly buffer PoolBlades {
    BladeGpu poolBlades[];
};
layout(std430, binding = BLADE_SSBO_BINDING) restrict writeonly buffer Blades { BladeGpu blades[]; };
layout(std430, binding = BLADE_REST_SSBO_BINDING) restrict writeonly buffer Rests { BladeRestGpu rests[]; };
layout(std430, binding = VISIBLE_INDEX_SSBO_BINDING) restrict writeonly buffer Visible {
    uint visibleIndices[];
};
layout(std430, binding = DRAW_COMMAND_SSBO_BINDING) restrict buffer Command { DrawCommandGpu command; };
layout(std430, binding = CULL_STATS_SSBO_BINDING) restrict buffer Stats { CullStatsGpu stats; };

shared uint groupCulled[4];  // orientation, frustum, thinned, occlusion
shared uint groupVisible;
shared uint groupBase;

void main() {
    uint lane = gl_LocalInvocationID.x;
    uint chunksPerTile = tiling.counts.y / uint(BLADE_WORKGROUP_SIZE);
    uint group = flatWorkGroup();
    if (group >= tiling.counts.x * chunksPerTile) return;  // uniform over the group
    TileDrawGpu drawn = tiles[group / chunksPerTile];
    uint k = (group % chunksPerTile) * uint(BLADE_WORKGROUP_SIZE) + lane;
    if (lane < 4u) groupCulled[lane] = 0u;
    if (lane == 0u) groupVisible = 0u;
    barrier();

    TileBlade b = tileRestBlade(drawn.tile.xy, instances[k], tiling);
    vec3 v0 = vec3(b.blade.v0_height);
    float limit = terrainDensityAt(vec2(v0.x, v0.z), tiling) *
                  keptFraction(distance(v0, vec3(cull.cameraPosition_m)), tiling);
    uint culledBy = 0u;
    BladeGpu blade = b.blade;
    if (b.threshold >= limit) {
        culledBy = CULL_TEST_DISTANCE;
    } else {
        if (drawn.tile.z != TILE_NOT_SIMULATED) {
            BladeGpu simulated = poolBlades[drawn.tile.z * tiling.counts.y + k];
            blade.v1_width = simulated.v1_width;
            blade.v2_stiffness = simulated.v2_stiffness;
        } else {
            blade = settledBlade(b, physics);
        }
        // A blade near its threshold narrows to nothing before it drops out, so thinning shows
        // no popping.
        blade.v1_width.w *= clamp((limit - b.threshold) / max(0.15 * limit, 1e-4), 0.0, 1.0);
        if (tiling.counts.w != 0u) {
            culledBy = cullBladeGeometric(blade, k, cull);
            if (culledBy == 0u && (cull.counts.y & CULL_TEST_OCCLUSION) != 0u &&
                bladeOccluded(blade, cull))
                culledBy = CULL_TEST_OCCLUSION;
        }
    }
    uint slot = 0u;
    if (culledBy == 0u) slot = atomicAdd(groupVisible, 1u);
    else atomicAdd(groupCulled[cullStatSlot(culledBy)], 1u);
    barrier();
    if (lane == 0u) groupBase = atomicAdd(command.vertexCount, groupVisible);
    barrier();
    uint index = groupBase + slot;
    // Past the buffers' end the blade is dropped; the draw never reads past them either
    // (TiledField clamps the count after this pass).
    if (culledBy == 0u && index < tiling.counts.z) {
        blades[index] = blade;
        rests[index] = b.rest;
        visibleIndices[index] = index;
    }
    if (lane == 0u) {
        atomicAdd(stats.culledOrientation, groupCulled[0]);
        atomicAdd(stats.culledFrustum, groupCulled[1]);
        atomicAdd(stats.culledDistance, groupCulled[2]);
        atomicAdd(stats.culledOcclusion, groupCulled[3]);
    }
}
