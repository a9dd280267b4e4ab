// Per-blade physics, Jahrmann & Wimmer 2017, Sec. 5: forces on the tip (recovery, gravity,
// wind), sphere collisions with a persistent collision strength, then the three validation steps.
// One invocation per blade. The math lives in common_physics.glsl, which the CPU reference
// (runtime/src/physics_reference.cpp) compiles as C++; this file only moves data, and its loop
// is mirrored line for line in physicsStepReference().
// Prepended by the loader: shared/blade_types.h, shared/physics_params.h, common_dispatch.glsl,
// common_physics.glsl.
layout(local_size_x = BLADE_WORKGROUP_SIZE) in;

layout(std140, binding = PHYSICS_UBO_BINDING) uniform PhysicsBlock { PhysicsParamsGpu params; };
layout(std430, binding = BLADE_SSBO_BINDING) restrict buffer Blades { BladeGpu blades[]; };
layout(std430, binding = BLADE_REST_SSBO_BINDING) restrict buffer Rests { BladeRestGpu rests[]; };
layout(std430, binding = COLLIDER_SSBO_BINDING) restrict readonly buffer Colliders {
    ColliderGpu colliders[];
};

void main() {
    uint i = flatInvocation();
    if (i >= params.counts.x) return;
    BladeGpu blade = blades[i];
    BladeRestGpu rest = rests[i];
    vec3 v0 = vec3(blade.v0_height);
    vec3 v1 = vec3(blade.v1_width);
    vec3 up = vec3(blade.up_direction);
    float h = blade.v0_height.w;

    vec3 v2 = forcedTip(blade, rest, params);

    vec3 d = vec3(0.0f);
    for (uint k = 0u; k < params.counts.y; ++k)
        d += bladeSphereTranslation(v0, v1, v2, colliders[k].center_radius_m);
    v2 += d;
    float eta = collisionStrength(rest.restV2_eta.w, d, h, params.collision.x, params.collision.z,
                                  params.gravityMix_dt.z);

    BladeCurve curve = validateBlade(v0, v2, up, h, vec3(rest.restV1_archetype),
                                     vec3(rest.restV2_eta), params.counts.z);
    blades[i].v1_width = vec4(curve.v1, blade.v1_width.w);
    blades[i].v2_stiffness = vec4(curve.v2, blade.v2_stiffness.w);
    rests[i].restV2_eta.w = eta;
}
