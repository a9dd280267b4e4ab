// Lighting shared by the opaque and the blade shaders.

// Lambert diffuse plus a constant sky ambient.
vec3 lambertWithAmbient(vec3 albedo, vec3 n, vec3 toLight, float lightIntensity, float ambient) {
    return albedo * (ambient + lightIntensity * max(dot(n, toLight), 0.0));
}

// Filmic-free display transform: clamp and gamma-encode linear colour for the 8-bit PNG.
vec3 linearToDisplay(vec3 linear) { return pow(clamp(linear, 0.0, 1.0), vec3(1.0 / 2.2)); }
