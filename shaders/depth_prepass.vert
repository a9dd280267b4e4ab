// Opaque meshes (grass ground, props, the terrain): drawn depth-only first, then shaded with
// depth EQUAL.
layout(location = 0) in vec3 aPosition_m;
layout(location = 1) in vec3 aNormal;

layout(std140, binding = FRAME_UBO_BINDING) uniform Frame { FrameGpu frame; };

uniform vec3 uOffset_m;  // where a moving collider's mesh is now; 0 for the scene's meshes
#ifdef SHADOW_PASS
uniform int uShadowCascade;  // which cascade of the shadow map is drawn
#endif

out vec3 vNormal;
out vec3 vWorld_m;
// The pre-pass and the terrain's shading are different programs with this vertex shader: the
// same position, bit for bit, lets the shading pass test depth EQUAL.
invariant gl_Position;

void main() {
    vNormal = aNormal;
    vWorld_m = aPosition_m + uOffset_m;
#ifdef SHADOW_PASS
    gl_Position = frame.lightClipFromWorld[uShadowCascade] * vec4(vWorld_m, 1.0);
#else
    gl_Position = frame.clipFromWorld * vec4(vWorld_m, 1.0);
#endif
}
