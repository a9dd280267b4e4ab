// Two-sided blade shading: diffuse on the lit side, translucency when lit from behind, and
// height-based ambient occlusion (roots sit in the shadow of the sward).
in vec3 teWorld_m;
in vec3 teNormal;
in float teHeightFraction;
in flat uint teBladeKey;
out vec4 fragColor;

layout(std140, binding = FRAME_UBO_BINDING) uniform Frame { FrameGpu frame; };

uniform vec3 uRootColor;          // linear albedo at the root
uniform vec3 uTipColor;           // linear albedo at the tip
uniform float uAmbient;           // sky ambient (fraction of albedo)
uniform float uTranslucency;      // fraction of back light transmitted through the blade
uniform float uAoAtRoot;          // ambient occlusion factor at v = 0 (1 = none)

// Small per-blade variation of hue so a meadow is not one flat colour.
float bladeHash(uint i) {
    i ^= i >> 16; i *= 0x7feb352du; i ^= i >> 15; i *= 0x846ca68bu; i ^= i >> 16;
    return float(i & 0xffffu) / 65535.0;
}

void main() {
#ifdef SHADOW_PASS
    return;  // depth only
#endif
    vec3 toLight = normalize(frame.lightDirection.xyz);
    float intensity = frame.lightDirection.w;
    vec3 toEye = normalize(frame.cameraPosition_time.xyz - teWorld_m);
    // Two-sided: the normal faces the viewer.
    vec3 n = normalize(teNormal);
    if (dot(n, toEye) < 0.0) n = -n;

    float variation = bladeHash(teBladeKey);
    vec3 albedo = mix(uRootColor, uTipColor, teHeightFraction) * (0.8 + 0.4 * variation);
    float ao = mix(uAoAtRoot, 1.0, teHeightFraction);

    float front = max(dot(n, toLight), 0.0);
    float back = max(dot(-n, toLight), 0.0);
    float direct = intensity * shadowedLight(teWorld_m, n, frame);
    vec3 color = albedo * ao * (uAmbient + direct * (front + uTranslucency * back));
    fragColor = vec4(linearToDisplay(withAerialPerspective(color, teWorld_m, frame)), 1.0);
}
