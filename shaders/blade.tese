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
uniform float uMinWidth_px;       // width correction: cross-sections never project thinner
#ifdef SHADOW_PASS
uniform int uShadowCascade;       // which cascade of the shadow map is drawn
#endif

patch in uint tcBladeIndex;
out vec3 teWorld_m;
out vec3 teNormal;
out float teHeightFraction;       // v
out flat uint teBladeKey;         // the same for a blade in every frame (its root's bits)

// The blade's cross-section at height v as its two edges, left (u = 0) and right (u = 1), in
// the paper's interpolation parameter t between c0 and c1 (Jahrmann & Wimmer 2017, Sec. 6.2,
// Fig. 6): every analytic shape is linear in u, t = mix(left, right, u).
//   quad t = u;  triangle t = u + 0.5 v - u v;  quadratic (meadow's, tip on the spine)
//   t = u - u v^2 + 0.5 v^2;  one-sided quadratic (the paper's) t = u - u v^2;
//   triangle-tip t = 0.5 + (u - 0.5) (1 - max(v - tau, 0) / (1 - tau)).
vec2 analyticShapeEdges(int shape, float v, float tau) {
    if (shape == BLADE_SHAPE_QUAD) return vec2(0.0, 1.0);
    if (shape == BLADE_SHAPE_TRIANGLE) return vec2(0.5 * v, 1.0 - 0.5 * v);
    if (shape == BLADE_SHAPE_ONE_SIDED_QUADRATIC) return vec2(0.0, 1.0 - v * v);
    if (shape == BLADE_SHAPE_TRIANGLE_TIP) {
        float half_ = 0.5 * (1.0 - max(v - tau, 0.0) / max(1.0 - tau, 1e-4));
        return vec2(0.5 - half_, 0.5 + half_);
    }
    return vec2(0.5 * v * v, 1.0 - 0.5 * v * v);  // BLADE_SHAPE_QUADRATIC
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

// Edges relative to the spine, in blade widths: t - 0.5 puts a symmetric shape's middle on the
// spine; a captured split of leftShare to the left (archetype.h, leftWidthFraction) moves the
// cross-section by (0.5 - leftShare) of its own width, so the left edge sits at -leftShare and
// the right at 1 - leftShare of the local width.
vec2 edgesAboutSpine(vec2 edges, float leftShare) {
    return edges - 0.5 + (0.5 - leftShare) * (edges.y - edges.x);
}

// Rodrigues' rotation of v about the unit axis k.
vec3 rotateAbout(vec3 v, vec3 k, float angle) {
    return v * cos(angle) + cross(k, v) * sin(angle) + k * dot(k, v) * (1.0 - cos(angle));
}

// Width correction (Jahrmann & Wimmer 2017, Eq. (24)): a blade whose local width projects
// thinner than uMinWidth_px breaks up into aliasing, so the cross-section at each height is
// widened to that size on screen. The projected width counts the blade's orientation: a width
// direction turned toward the viewing ray by angle theta projects sin(theta) of its length, and
// is widened by 1 / sin(theta) up to MAX_OBLIQUE_WIDENING (the orientation test culls blades
// more edge-on than that). Per height, not once per blade: a tapering tip keeps the minimum size
// up to its end instead of falling apart into dots.
const float MAX_OBLIQUE_WIDENING = 4.0;
float correctedAcross_m(float across_m, vec3 widthDirection, vec3 fromCamera) {
    float facing = length(cross(widthDirection, normalize(fromCamera)));  // sin(theta)
    float minAcross_m = uMinWidth_px * uPixelSize_perM * length(fromCamera) /
                        max(facing, 1.0 / MAX_OBLIQUE_WIDENING);
    return max(across_m, minAcross_m);
}

// 3D displacement of Sec. 6.2: a ridge along the blade's middle, vanishing toward the tip.
float displacementRidge(float u, float v) { return 0.5 - abs(u - 0.5) * (1.0 - v); }

void main() {
    uint i = tcBladeIndex;
    BladeGpu blade = blades[i];
    uint archetype = uint(rests[i].restV1_archetype.w);
    ArchetypeGpu look = archetypes[archetype];
    float u = gl_TessCoord.x, v = gl_TessCoord.y;

    vec3 tangent;
    vec3 c = bladeSpinePoint(blade.v0_height.xyz, blade.v1_width.xyz, blade.v2_stiffness.xyz, v, tangent);
    // The captured twist turns the width direction about the spine, linearly from base to tip.
    vec3 bitangent = rotateAbout(bladeWidthDirection(blade.up_direction.xyz, blade.up_direction.w),
                                 tangent, look.sides.y * v);
    vec3 normal = normalize(cross(tangent, bitangent));

    int shape = uShapeOverride >= 0 ? uShapeOverride : int(look.shape.x);
    bool useProfile = uShapeOverride < 0 && look.shape.z > 0.5;
    float profile = profileWidth(archetype, v);
    vec2 edges = useProfile ? vec2(0.5 - 0.5 * profile, 0.5 + 0.5 * profile)
                            : analyticShapeEdges(shape, v, look.shape.y);
    edges = edgesAboutSpine(edges, look.sides.x) * blade.v1_width.w;  // metres

    float centre_m = 0.5 * (edges.x + edges.y);
    float across_m = correctedAcross_m(edges.y - edges.x, bitangent, c - frame.cameraPosition_time.xyz);
    vec3 p = c + (centre_m + (u - 0.5) * across_m) * bitangent;
    if (uDisplacement) p += blade.v1_width.w * displacementRidge(u, v) * normal;

    teWorld_m = p;
    teNormal = normal;
    teHeightFraction = v;
    // Not the index: a tiled scene's blades are emitted anew each frame, in any order.
    teBladeKey = floatBitsToUint(blade.v0_height.x) * 0x9e3779b1u ^ floatBitsToUint(blade.v0_height.z);
#ifdef SHADOW_PASS
    gl_Position = frame.lightClipFromWorld[uShadowCascade] * vec4(p, 1.0);
#else
    gl_Position = frame.clipFromWorld * vec4(p, 1.0);
#endif
}
