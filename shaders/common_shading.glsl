// Lighting shared by the opaque and the blade shaders.

// Lambert diffuse plus a constant sky ambient.
vec3 lambertWithAmbient(vec3 albedo, vec3 n, vec3 toLight, float lightIntensity, float ambient) {
    return albedo * (ambient + lightIntensity * max(dot(n, toLight), 0.0));
}

// Filmic-free display transform: clamp and gamma-encode linear colour for the 8-bit PNG.
vec3 linearToDisplay(vec3 linear) { return pow(clamp(linear, 0.0, 1.0), vec3(1.0 / 2.2)); }

vec3 displayToLinear(vec3 display) { return pow(clamp(display, 0.0, 1.0), vec3(2.2)); }

// The sky's colour along a view direction: the horizon colour up to the horizon, then toward
// the zenith colour (faster near the horizon, as a clear sky brightens there).
vec3 skyLinear(vec3 direction, FrameGpu f) {
    float up = clamp(normalize(direction).y, 0.0, 1.0);
    return mix(f.horizon.xyz, f.zenith.xyz, sqrt(up));
}

// Aerial perspective: light from a surface d away keeps exp(-d / fog distance) of itself, the
// rest is the haze's colour (the sky at the horizon), so the ground meets the sky at the horizon.
vec3 withAerialPerspective(vec3 linear, vec3 world, FrameGpu f) {
    if (f.horizon.w <= 0.0) return linear;
    float kept = exp(-distance(world, f.cameraPosition_time.xyz) / f.horizon.w);
    return mix(f.horizon.xyz, linear, kept);
}

// The share of direct light that reaches a point (1 lit, 1 - strength in shadow), from the
// nearest shadow cascade that holds it (cascade c is the c-th square of the map, left to right),
// with 2 x 2 percentage-closer filtering (hardware comparison, bilinear). Points outside every
// cascade are lit.
layout(binding = SHADOW_TEXTURE_UNIT) uniform sampler2DShadow shadowMap;
float shadowedLight(vec3 world, vec3 n, FrameGpu f) {
    float strength = f.zenith.w;
    if (strength <= 0.0) return 1.0;
    vec2 texel = 1.0 / vec2(textureSize(shadowMap, 0));
    // Two texels of margin (in a cascade's own units) so the filter never reads a neighbour.
    float margin = 2.0 * texel.x * float(SHADOW_CASCADES);
    for (int c = 0; c < SHADOW_CASCADES; ++c) {
        vec4 q = f.lightClipFromWorld[c] * vec4(world + 0.02 * n, 1.0);
        vec3 p = q.xyz / q.w * 0.5 + 0.5;
        if (any(lessThan(p, vec3(margin, margin, 0.0))) ||
            any(greaterThan(p, vec3(1.0 - margin, 1.0 - margin, 1.0))))
            continue;
        vec2 atlas = vec2((p.x + float(c)) / float(SHADOW_CASCADES), p.y);
        float lit = 0.0;
        for (int i = 0; i < 4; ++i) {
            vec2 o = (vec2(i & 1, i >> 1) - 0.5) * texel;
            lit += texture(shadowMap, vec3(atlas + o, p.z - 0.0015));
        }
        return 1.0 - strength * (1.0 - 0.25 * lit);
    }
    return 1.0;
}
