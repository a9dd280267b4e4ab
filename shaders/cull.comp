// Per-blade culling, Jahrmann & Wimmer 2017, Sec. 5.2, into an indirect draw. One workgroup per
// patch: the patch bounds are tested first (uniform over the group), then the group walks the
// patch's blades BLADE_WORKGROUP_SIZE at a time: orientation, frustum, distance (Eq. (14)-(15),
// common_culling.glsl) and occlusion against the opaque depth pre-pass. Survivors are compacted
// per group (one global atomicAdd per chunk) into the visible-index buffer, whose count is the
// vertexCount of the DrawArraysIndirect command. Culled blades are counted per test in shared
// memory and added to the stats once per group.
//
// The command and the stats are reset by the host (glClearNamedBufferSubData + glMemoryBarrier)
// before this dispatch: barrier() orders nothing between workgroups.
// Prepended by the loader: shared/blade_types.h, shared/physics_params.h, shared/cull_params.h,
// common_dispatch.glsl, common_physics.glsl, common_culling.glsl, common_culling_depth.glsl.
layout(local_size_x = BLADE_WORKGROUP_SIZE) in;

layout(std140, binding = CULL_UBO_BINDING) uniform CullBlock { CullParamsGpu params; };
layout(std430, binding = BLADE_SSBO_BINDING) restrict readonly buffer Blades { BladeGpu blades[]; };
layout(std430, binding = PATCH_SSBO_BINDING) restrict readonly buffer Patches { PatchGpu patches[]; };
layout(std430, binding = VISIBLE_INDEX_SSBO_BINDING) restrict writeonly buffer Visible {
    uint visibleIndices[];
};
layout(std430, binding = DRAW_COMMAND_SSBO_BINDING) restrict buffer Command { DrawCommandGpu command; };
layout(std430, binding = CULL_STATS_SSBO_BINDING) restrict buffer Stats { CullStatsGpu stats; };

shared uint groupCulled[4];  // orientation, frustum, distance, occlusion
shared uint groupVisible;
shared uint groupBase;

void main() {
    uint lane = gl_LocalInvocationID.x;
    if (flatWorkGroup() >= params.counts.x) return;  // uniform over the group
    PatchGpu bladePatch = patches[flatWorkGroup()];
    uint first = bladePatch.range.x;
    uint count = bladePatch.range.y;
    if (lane < 4u) groupCulled[lane] = 0u;
    barrier();

    bool patchCulled = (params.counts.y & CULL_TEST_FRUSTUM) != 0u &&
                       patchOutsideFrustum(params.clipFromWorld, vec3(bladePatch.boundsMin_m),
                                           vec3(bladePatch.boundsMax_m), params.orientationFrustum.y);
    if (patchCulled) {
        if (lane == 0u) atomicAdd(stats.culledFrustum, count);
        return;  // uniform over the group
    }

    for (uint chunk = 0u; chunk < count; chunk += BLADE_WORKGROUP_SIZE) {
        if (lane == 0u) groupVisible = 0u;
        barrier();
        uint id = chunk + lane;
        uint slot = 0u;
        bool visible = false;
        if (id < count) {
            BladeGpu blade = blades[first + id];
            uint culledBy = cullBladeGeometric(blade, id, params);
            if (culledBy == 0u && (params.counts.y & CULL_TEST_OCCLUSION) != 0u &&
                bladeOccluded(blade, params))
                culledBy = CULL_TEST_OCCLUSION;
            if (culledBy == 0u) {
                visible = true;
                slot = atomicAdd(groupVisible, 1u);
            } else {
                atomicAdd(groupCulled[cullStatSlot(culledBy)], 1u);
            }
        }
        barrier();
        if (lane == 0u) groupBase = atomicAdd(command.vertexCount, groupVisible);
        barrier();
        if (visible) visibleIndices[groupBase + slot] = first + id;
        barrier();  // groupVisible / groupBase are rewritten by the next chunk
    }

    if (lane == 0u) {
        atomicAdd(stats.culledOrientation, groupCulled[0]);
        atomicAdd(stats.culledFrustum, groupCulled[1]);
        atomicAdd(stats.culledDistance, groupCulled[2]);
        atomicAdd(stats.culledOcclusion, groupCulled[3]);
    }
}
