// Per-blade culling of Jahrmann & Wimmer 2017, Sec. 5.2: orientation (Eq. (14)), view frustum,
// distance (Eq. (15)) and occlusion, plus the patch bounds test that runs first.
//
// ONE TEXT FOR GPU AND CPU, like common_physics.glsl (which it needs, for the blade's width
// direction): shaders/cull.comp gets it from the loader, runtime/src/culling_reference.cpp
// compiles it as C++ with glm in scope. Common subset of GLSL 4.50 and C++20 only.

// A point is inside the frustum when -w' <= x, y, z <= w' with w' = w (1 + tolerance): the
// tolerance is in NDC units, so a blade whose three points lie just outside (its curve or its
// width still reaching in) is kept.
bool clipPointInFrustum(vec4 q, float tolerance) {
    float w = q.w * (1.0f + tolerance);
    return abs(q.x) <= w && abs(q.y) <= w && abs(q.z) <= w;
}

// Patch bounds, Jahrmann & Wimmer 2017, Sec. 4 / 5.2: a patch whose box has all eight corners
// outside one clip plane cannot show any blade (the planes are linear in homogeneous clip
// coordinates, so this also holds for corners behind the camera).
bool patchOutsideFrustum(mat4 clipFromWorld, vec3 boundsMin, vec3 boundsMax, float tolerance) {
    bool allLeft = true, allRight = true, allBelow = true, allAbove = true, allNear = true,
         allFar = true;
    for (int k = 0; k < 8; ++k) {
        vec3 corner = vec3((k & 1) != 0 ? boundsMax.x : boundsMin.x,
                           (k & 2) != 0 ? boundsMax.y : boundsMin.y,
                           (k & 4) != 0 ? boundsMax.z : boundsMin.z);
        vec4 q = clipFromWorld * vec4(corner, 1.0f);
        float w = q.w * (1.0f + tolerance);
        allLeft = allLeft && q.x < -w;
        allRight = allRight && q.x > w;
        allBelow = allBelow && q.y < -w;
        allAbove = allAbove && q.y > w;
        allNear = allNear && q.z < -w;
        allFar = allFar && q.z > w;
    }
    return allLeft || allRight || allBelow || allAbove || allNear || allFar;
}

// Orientation test, Jahrmann & Wimmer 2017, Eq. (14): a blade seen edge-on (viewing direction
// dir_c nearly parallel to its width direction dir_b) is thinner than a pixel: culled when
// |dir_c . dir_b| > threshold (0.9 in the paper). dir_c is taken per blade, from the camera to v0,
// so the test stays right away from the image centre.
bool orientationCulled(vec3 cameraPosition, vec3 v0, vec3 dir_b, float threshold) {
    vec3 dir_c = safeNormalize(v0 - cameraPosition);
    return abs(dot(dir_c, dir_b)) > threshold;
}

// View-frustum test, Jahrmann & Wimmer 2017, Sec. 5.2: v0, the curve midpoint m and v2 are
// projected; the blade is culled when all three lie outside the (tolerance-widened) frustum.
bool frustumCulled(mat4 clipFromWorld, vec3 v0, vec3 m, vec3 v2, float tolerance) {
    return !clipPointInFrustum(clipFromWorld * vec4(v0, 1.0f), tolerance) &&
           !clipPointInFrustum(clipFromWorld * vec4(m, 1.0f), tolerance) &&
           !clipPointInFrustum(clipFromWorld * vec4(v2, 1.0f), tolerance);
}

// Distance test, Jahrmann & Wimmer 2017, Eq. (15): with d_proj the camera's distance from v0 in
// the blade's ground plane, blade number id of its patch is culled when
//   id mod n > floor(n (1 - d_proj / d_max)),
// so n distance levels keep n, n - 1, ..., 1 of every n blades, and none beyond d_max. This is
// why blade indices within a patch are locality-sorted: every level thins the patch evenly.
bool distanceCulled(vec3 cameraPosition, vec3 v0, vec3 up, uint id, float d_max, uint n) {
    vec3 c = cameraPosition - v0;
    float d_proj = length(c - up * dot(c, up));
    return float(id % n) > floor(float(n) * (1.0f - d_proj / d_max));
}

// Occlusion test, Jahrmann & Wimmer 2017, Sec. 5.2, against the opaque objects' depth pre-pass.
// A projected point is testable when it lies in front of the camera and inside the viewport.
bool clipPointInViewport(vec4 q) {
    return q.w > 0.0f && abs(q.x) <= q.w && abs(q.y) <= q.w && abs(q.z) <= q.w;
}

// The depth texel under a testable point (texelFetch coordinates, clamped to the image).
ivec2 depthTexel(vec4 q, uvec2 size) {
    vec2 uv = vec2(q.x / q.w, q.y / q.w) * 0.5f + vec2(0.5f);
    ivec2 texel = ivec2(floor(uv * vec2(size)));
    return clamp(texel, ivec2(0), ivec2(size) - ivec2(1));
}

// Eye-space distance (m) of a window depth z in [0, 1] of a standard OpenGL perspective.
float viewDepth_m(float z, float near_m, float far_m) {
    return near_m * far_m / (far_m - z * (far_m - near_m));
}

// A point is occluded when it lies more than `bias` behind the opaque depth under it.
bool pointOccluded(vec4 q, float sceneDepth, float near_m, float far_m, float bias_m) {
    float z = 0.5f * (q.z / q.w) + 0.5f;
    return viewDepth_m(z, near_m, far_m) > viewDepth_m(sceneDepth, near_m, far_m) + bias_m;
}

// Orientation, frustum and distance tests of one blade in order: the CULL_TEST_* bit of the
// first test that culls it, 0 when it survives them (occlusion runs after, in the caller, because
// GLSL and C++ read the depth image differently).
uint cullBladeGeometric(BladeGpu blade, uint id, CullParamsGpu p) {
    vec3 v0 = vec3(blade.v0_height);
    vec3 v1 = vec3(blade.v1_width);
    vec3 v2 = vec3(blade.v2_stiffness);
    vec3 up = vec3(blade.up_direction);
    vec3 cameraPosition = vec3(p.cameraPosition_m);
    uint tests = p.counts.y;
    if ((tests & CULL_TEST_ORIENTATION) != 0u &&
        orientationCulled(cameraPosition, v0, bladeWidthAxis(up, blade.up_direction.w),
                          p.orientationFrustum.x))
        return CULL_TEST_ORIENTATION;
    if ((tests & CULL_TEST_FRUSTUM) != 0u &&
        frustumCulled(p.clipFromWorld, v0, bezierMidpoint(v0, v1, v2), v2, p.orientationFrustum.y))
        return CULL_TEST_FRUSTUM;
    if ((tests & CULL_TEST_DISTANCE) != 0u &&
        distanceCulled(cameraPosition, v0, up, id, p.distanceLevels.x,
                       max(uint(p.distanceLevels.y), 1u)))
        return CULL_TEST_DISTANCE;
    return 0u;
}
