// Shading of the opaque meshes; with the colour mask off the same program is the depth pre-pass.
in vec3 vNormal;
out vec4 fragColor;

layout(std140, binding = FRAME_UBO_BINDING) uniform Frame { FrameGpu frame; };

uniform vec3 uAlbedo;   // linear
uniform float uAmbient;

void main() {
    vec3 n = normalize(vNormal);
    vec3 color = lambertWithAmbient(uAlbedo, n, normalize(frame.lightDirection.xyz),
                                    frame.lightDirection.w, uAmbient);
    fragColor = vec4(linearToDisplay(color), 1.0);
}
