// Shading of the opaque meshes; with the colour mask off the same program is the depth pre-pass.
in vec3 vNormal;
in vec3 vWorld_m;
out vec4 fragColor;

layout(std140, binding = FRAME_UBO_BINDING) uniform Frame { FrameGpu frame; };

uniform vec3 uAlbedo;   // linear
uniform float uAmbient;

void main() {
    vec3 n = normalize(vNormal);
    vec3 toLight = normalize(frame.lightDirection.xyz);
    float direct = frame.lightDirection.w * max(dot(n, toLight), 0.0) * shadowedLight(vWorld_m, n, frame);
    vec3 color = uAlbedo * (uAmbient + direct);
    fragColor = vec4(linearToDisplay(withAerialPerspective(color, vWorld_m, frame)), 1.0);
}
