// Tile instancing (Fan & Sheng, Sec. 4.5): a tile's blade from the shared patch, on the terrain.
// Needs shared/tiling_types.h, shared/physics_params.h, common_physics.glsl and the terrain
// height texture.
layout(binding = TERRAIN_HEIGHT_TEXTURE_UNIT) uniform sampler2D terrainHeight;
layout(binding = TERRAIN_DENSITY_TEXTURE_UNIT) uniform sampler2D terrainDensity;

// Height of the terrain at world xz: the grid sampled bilinearly, texel centres on the samples
// (HeightField::heightAt).
float terrainHeightAt(vec2 xz, TilingParamsGpu t) {
    vec2 size = vec2(textureSize(terrainHeight, 0));
    vec2 g = clamp((xz - t.terrain.xy) / t.terrain.zw, 0.0, 1.0) * (size - 1.0);
    return texture(terrainHeight, (g + 0.5) / size).r;
}

vec3 terrainNormalAt(vec2 xz, TilingParamsGpu t) {
    vec2 d = t.terrain.zw / (vec2(textureSize(terrainHeight, 0)) - 1.0);
    float dx = terrainHeightAt(xz + vec2(d.x, 0.0), t) - terrainHeightAt(xz - vec2(d.x, 0.0), t);
    float dz = terrainHeightAt(xz + vec2(0.0, d.y), t) - terrainHeightAt(xz - vec2(0.0, d.y), t);
    return normalize(vec3(-dx / (2.0 * d.x), 1.0, -dz / (2.0 * d.y)));
}

// The density map at world xz, in [0, 1] (white everywhere when the scene has none).
float terrainDensityAt(vec2 xz, TilingParamsGpu t) {
    return texture(terrainDensity, (xz - t.terrain.xy) / t.terrain.zw).r;
}

// A tile's turn of the patch: a quarter turn k (0..3) and a shift of the thresholds, from a hash
// of its position, so neighbouring tiles neither repeat the same blades nor thin the same ones.
uint tileHash(uvec2 tile) { return windHash(tile.x * 0x9e3779b1u ^ windHash(tile.y + 0x632be5abu)); }

// Fraction of the blades kept at distance d (Boulanger et al.: blades drop out by their density
// threshold): all up to the full-density distance, then as (full / d)^2, so the drawn count
// grows with the log of the near distance instead of its square; and to nothing over the
// transition band before the near distance, where the far field takes over.
float keptFraction(float d, TilingParamsGpu t) {
    float full = t.tile.w;
    float thinned = d <= full ? 1.0 : (full * full) / (d * d);
    float band = max(t.tile.z, 1e-4);
    return thinned * (1.0 - smoothstep(t.tile.y - band, t.tile.y, d));
}

struct TileBlade {
    BladeGpu blade;
    BladeRestGpu rest;
    float threshold;  // the blade's density threshold in this tile
};

// Blade k of the patch placed in `tile`: its root on the terrain, its rest shape turned with the
// tile and stood on the terrain's normal, stiffness and archetype from the patch.
TileBlade tileRestBlade(uvec2 tile, TileInstanceGpu inst, TilingParamsGpu t) {
    uint h = tileHash(tile);
    uint turn = h & 3u;
    float size = t.tile.x;
    vec2 p = vec2(inst.place.x, inst.place.z);
    // Quarter turns about the tile's centre map the square onto itself.
    vec2 c = p - 0.5 * size;
    for (uint i = 0u; i < turn; ++i) c = vec2(-c.y, c.x);
    vec2 xz = t.terrain.xy + vec2(tile) * size + c + 0.5 * size;
    float angle = inst.place.w + float(turn) * 0.5 * kPhysicsPi;

    vec3 up = terrainNormalAt(xz, t);
    vec3 w = bladeWidthAxis(up, angle);
    vec3 d = cross(w, up);
    vec3 v0 = vec3(xz.x, terrainHeightAt(xz, t), xz.y);
    vec3 v1 = v0 + inst.restV1_width.x * d + inst.restV1_width.y * up + inst.restV1_width.z * w;
    vec3 v2 = v0 + inst.restV2_height.x * d + inst.restV2_height.y * up + inst.restV2_height.z * w;

    TileBlade b;
    b.blade.v0_height = vec4(v0, inst.restV2_height.w);
    b.blade.v1_width = vec4(v1, inst.restV1_width.w);
    b.blade.v2_stiffness = vec4(v2, inst.look.y);
    b.blade.up_direction = vec4(up, angle);
    b.rest.restV1_archetype = vec4(v1, inst.look.x);
    b.rest.restV2_eta = vec4(v2, 0.0);
    b.threshold = fract(inst.look.z + float(h >> 8u) * (1.0 / 16777216.0));
    return b;
}

// The pose a blade settles into under gravity and this instant's wind, for tiles that are not
// simulated: the fixed point of one physics step (Jahrmann & Wimmer 2017, Sec. 5.1,
// v2 += (r + g + w) dt with r = (Iv2 - v2) s) is v2 = Iv2 + (g + w) / s, then the three
// validation steps (Eq. (10)-(13)). The wind is taken at the rest pose.
BladeGpu settledBlade(TileBlade b, PhysicsParamsGpu p) {
    BladeGpu blade = b.blade;
    vec3 v0 = vec3(blade.v0_height);
    float h = blade.v0_height.w;
    float s = max(blade.v2_stiffness.w, 1e-3);
    vec3 up = vec3(blade.up_direction);
    vec3 Iv2 = vec3(b.rest.restV2_eta);
    vec3 gE = environmentalGravity(p, v0);
    vec3 g = totalGravity(gE, frontGravity(gE, bladeFrontDirection(up, blade.up_direction.w)));
    vec3 wi = windInfluence(p, v0);
    vec3 wind = windForce(wi, windDirectionalAlignment(wi, v0, Iv2), windHeightRatio(v0, Iv2, up, h));
    vec3 v2 = Iv2 + (g + wind) / s;
    BladeCurve curve = validateBlade(v0, v2, up, h, vec3(b.rest.restV1_archetype), Iv2, p.counts.z);
    blade.v1_width = vec4(curve.v1, blade.v1_width.w);
    blade.v2_stiffness = vec4(curve.v2, blade.v2_stiffness.w);
    return blade;
}
