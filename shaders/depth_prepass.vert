// Opaque meshes (grass ground and props): drawn depth-only first, then shaded with depth EQUAL.
layout(location = 0) in vec3 aPosition_m;
layout(location = 1) in vec3 aNormal;

layout(std140, binding = FRAME_UBO_BINDING) uniform Frame { FrameGpu frame; };

uniform vec3 uOffset_m;  // where a moving collider's mesh is now; 0 for the scene's meshes

out vec3 vNormal;

void main() {
    vNormal = aNormal;
    gl_Position = frame.clipFromWorld * vec4(aPosition_m + uOffset_m, 1.0);
}
