// Tessellation level of a blade from its projected size (Jahrmann & Wimmer 2017, Sec. 6):
// one segment per BLADE_PIXELS_PER_SEGMENT pixels of projected spine length.
layout(vertices = 1) out;

layout(std430, binding = BLADE_SSBO_BINDING) readonly buffer Blades { BladeGpu blades[]; };
layout(std140, binding = FRAME_UBO_BINDING) uniform Frame { FrameGpu frame; };

uniform float uMaxTessLevel;      // segments along the blade at most
uniform int uAcrossSegments;      // 1, or 2 with 3D displacement (needs a vertex at u = 0.5)

in flat uint vBladeIndex[];
patch out uint tcBladeIndex;  // one blade per patch

vec2 toPixels(vec3 world) {
    vec4 clip = frame.clipFromWorld * vec4(world, 1.0);
    // Points behind the camera are pushed to the near plane; the level only needs a length.
    return (clip.xy / max(clip.w, frame.viewport_px.z)) * 0.5 * frame.viewport_px.xy;
}

void main() {
    uint i = vBladeIndex[0];
    tcBladeIndex = i;
    BladeGpu blade = blades[i];
    vec3 v0 = blade.v0_height.xyz, v1 = blade.v1_width.xyz, v2 = blade.v2_stiffness.xyz;
    // The control polygon bounds the curve's length from above, the chord from below: their mean.
    float polygon_px = length(toPixels(v1) - toPixels(v0)) + length(toPixels(v2) - toPixels(v1));
    float chord_px = length(toPixels(v2) - toPixels(v0));
    float length_px = 0.5 * (polygon_px + chord_px);
    float along = clamp(ceil(length_px / BLADE_PIXELS_PER_SEGMENT), 1.0, uMaxTessLevel);
    float across = float(uAcrossSegments);
    gl_TessLevelOuter[0] = along;   // edge u = 0
    gl_TessLevelOuter[1] = across;  // edge v = 0
    gl_TessLevelOuter[2] = along;   // edge u = 1
    gl_TessLevelOuter[3] = across;  // edge v = 1
    gl_TessLevelInner[0] = across;
    gl_TessLevelInner[1] = along;
}
