// The culling that reads the opaque depth pre-pass, shared by the passes that cull blades
// (cull.comp, tiles_emit.comp). GLSL only: the CPU reference reads its depth image its own way
// (culling_reference.cpp). Needs shared/cull_params.h, common_physics.glsl, common_culling.glsl.
layout(binding = CULL_DEPTH_TEXTURE_UNIT) uniform sampler2D opaqueDepth;

// Where a CULL_TEST_* bit is counted in CullStatsGpu: orientation, frustum, distance, occlusion.
uint cullStatSlot(uint test) {
    return test == CULL_TEST_ORIENTATION ? 0u : test == CULL_TEST_FRUSTUM ? 1u
         : test == CULL_TEST_DISTANCE ? 2u : 3u;
}

bool behindOpaque(vec4 q, CullParamsGpu p) {
    if (!clipPointInViewport(q)) return false;
    float sceneDepth = texelFetch(opaqueDepth, depthTexel(q, p.counts.zw), 0).r;
    return pointOccluded(q, sceneDepth, p.depthRange_m.x, p.depthRange_m.y, p.depthRange_m.z);
}

// Occlusion test (Jahrmann & Wimmer 2017, Sec. 5.2): hidden when root, midpoint and tip all lie
// behind the opaque depth.
bool bladeOccluded(BladeGpu blade, CullParamsGpu p) {
    vec3 v0 = vec3(blade.v0_height);
    vec3 v2 = vec3(blade.v2_stiffness);
    vec3 m = bezierMidpoint(v0, vec3(blade.v1_width), v2);
    return behindOpaque(p.clipFromWorld * vec4(v0, 1.0f), p) &&
           behindOpaque(p.clipFromWorld * vec4(m, 1.0f), p) &&
           behindOpaque(p.clipFromWorld * vec4(v2, 1.0f), p);
}
