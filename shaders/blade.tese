// Blade surface from its spine and width (Jahrmann & Wimmer 2017, Sec. 6): u runs across the
// blade (0..1), v from root (0) to tip (1).
layout(quads, equal_spacing, ccw) in;

layout(std430, binding = BLADE_SSBO_BINDING) readonly buffer Blades { BladeGpu blades[]; };
layout(std430, binding = BLADE_REST_SSBO_BINDING) readonly buffer BladeRests { BladeRestGpu rests[]; };
layout(std430, binding = ARCHETYPE_SSBO_BINDING) readonly buffer Archetypes { ArchetypeGpu archetypes[]; };
layout(std140, binding = FRAME_UBO_BINDING) uniform Frame { FrameGpu frame; };

uniform int uShapeOverride;       // -1: each archetype's own shape; else a BLADE_SHAPE_* for all
uniform bool uDisplacement;       // 3D displacement along the normal (Sec. 6.2)
uniform float uPixelSize_perM;    // world size of one pixel at 1 m distance (m/m)
uniform float uMinWidth_px;       // width correction: blades never project thinner than this

patch in uint tcBladeIndex;
out vec3 teWorld_m;
out vec3 teNormal;
out float teHeightFraction;       // v
out flat uint teBladeIndex;

// Analytic shapes: interpolation parameter t between the two blade edges c0 and c1 for the
// domain point (u, v), Jahrmann & Wimmer 2017, Sec. 6.2 (Fig. 6).
float shapeQuad(float u, float v) { return u; }
float shapeTriangle(float u, float v) { return u + 0.5 * v - u * v; }
float shapeQuadratic(float u, float v) { return u - u * v * v + 0.5 * v * v; }
float shapeTriangleTip(float u, float v, float tau) {
    return 0.5 + (u - 0.5) * (1.0 - max(v - tau, 0.0) / max(1.0 - tau, 1e-4));
}

// The captured width profile (relative, 1 = widest) at height fraction v: the profile is sampled
// over arc length, v is the curve parameter; the two agree closely for the gentle bends of grass.
float profileWidth(uint archetype, float v) {
    float x = clamp(v, 0.0, 1.0) * float(ARCHETYPE_WIDTH_SAMPLES - 1);
    int i = min(int(x), ARCHETYPE_WIDTH_SAMPLES - 2);
    float f = x - float(i);
    float a = archetypes[archetype].widthProfile[i / 4][i % 4];
    float b = archetypes[archetype].widthProfile[(i + 1) / 4][(i + 1) % 4];
    return mix(a, b, f);
}

// 3D displacement of Sec. 6.2: a ridge along the blade's middle, vanishing toward the tip.
float displacementRidge(float u, float v) { return 0.5 - abs(u - 0.5) * (1.0 - v); }

void main() {
    uint i = tcBladeIndex;
    BladeGpu blade = blades[i];
    uint archetype = uint(rests[i].restV1_archetype.w);
    float u = gl_TessCoord.x, v = gl_TessCoord.y;

    vec3 tangent;
    vec3 c = bladeSpinePoint(blade.v0_height.xyz, blade.v1_width.xyz, blade.v2_stiffness.xyz, v, tangent);
    vec3 bitangent = bladeWidthDirection(blade.up_direction.xyz, blade.up_direction.w);
    vec3 normal = normalize(cross(tangent, bitangent));

    // Width correction: a blade seen from afar would project thinner than a pixel and break up
    // into aliasing; it is widened to at least uMinWidth_px (its area, not its look, changes).
    float distance_m = length(c - frame.cameraPosition_time.xyz);
    float width_m = max(blade.v1_width.w, uMinWidth_px * uPixelSize_perM * distance_m);

    int shape = uShapeOverride >= 0 ? uShapeOverride : int(archetypes[archetype].shape.x);
    bool useProfile = uShapeOverride < 0 && archetypes[archetype].shape.z > 0.5;
    float t;
    if (useProfile) t = 0.5 + (u - 0.5) * profileWidth(archetype, v);
    else if (shape == BLADE_SHAPE_QUAD) t = shapeQuad(u, v);
    else if (shape == BLADE_SHAPE_TRIANGLE) t = shapeTriangle(u, v);
    else if (shape == BLADE_SHAPE_TRIANGLE_TIP) t = shapeTriangleTip(u, v, archetypes[archetype].shape.y);
    else t = shapeQuadratic(u, v);

    vec3 c0 = c - 0.5 * width_m * bitangent;
    vec3 c1 = c + 0.5 * width_m * bitangent;
    vec3 p = mix(c0, c1, t);
    if (uDisplacement) p += width_m * displacementRidge(u, v) * normal;

    teWorld_m = p;
    teNormal = normal;
    teHeightFraction = v;
    teBladeIndex = i;
    gl_Position = frame.clipFromWorld * vec4(p, 1.0);
}
