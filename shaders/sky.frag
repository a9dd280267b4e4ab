// A sky gradient from the horizon to the zenith (light.zenith_color).
in vec2 vNdc;
out vec4 fragColor;
layout(std140, binding = FRAME_UBO_BINDING) uniform Frame { FrameGpu frame; };
void main() {
    vec4 far = frame.worldFromClip * vec4(vNdc, 1.0, 1.0);
    vec3 direction = far.xyz / far.w - frame.cameraPosition_time.xyz;
    fragColor = vec4(linearToDisplay(skyLinear(direction, frame)), 1.0);
}
