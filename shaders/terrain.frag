// A tiled scene's ground: the soil, and over it the far field where the near blades have thinned
// out (Habel, Wimmer & Jeschke 2007: grass as slices traced in the fragment shader; Boulanger et
// al.: density thresholds hand the field from geometry to slices). The view ray is followed
// through the grass layer above this point, across the vertical slice planes of the tile's
// slabs (x and z), front to back; each crossing adds the slice's coverage there, thinned by the
// density map and by how much of the field the near blades still draw.
// Prepended: shared/blade_types.h, shared/physics_params.h, shared/tiling_types.h,
// common_physics.glsl, common_tiles.glsl, common_shading.glsl.
in vec3 vNormal;
in vec3 vWorld_m;
out vec4 fragColor;

layout(std140, binding = FRAME_UBO_BINDING) uniform Frame { FrameGpu frame; };
layout(std140, binding = TILING_UBO_BINDING) uniform TilingBlock { TilingParamsGpu tiling; };
layout(binding = FAR_FIELD_TEXTURE_UNIT) uniform sampler2DArray slices;

uniform vec3 uAlbedo;         // the soil, linear
uniform float uAmbient;
uniform bool uFarField;
uniform int uSlicesPerAxis;
uniform float uSliceSpacing_m;
uniform float uSliceHeight_m;
uniform float uPixelSize_perM;  // world size of one pixel at 1 m
uniform float uTranslucency;
// A slice's averages per band of height, band 0 at the ground (FarFieldSlices).
const int HEIGHT_BANDS = 8;
uniform float uBandCoverage[HEIGHT_BANDS];
uniform vec3 uBandAlbedo[HEIGHT_BANDS];

const int MAX_SLICE_CROSSINGS = 12;

// Lighting of the slices' blades, averaged over blade orientations: sky ambient, and the direct
// light on a vertical blade's lit side plus what shines through from behind.
vec3 litBlade(vec3 albedo, float direct) {
    return albedo * (uAmbient + direct * (0.5 + 0.5 * uTranslucency) * 0.45);
}

void main() {
    vec3 n = normalize(vNormal);
    vec3 toLight = normalize(frame.lightDirection.xyz);
    float shadow = shadowedLight(vWorld_m, n, frame);
    float direct = frame.lightDirection.w * shadow;
    vec3 soil = uAlbedo * (uAmbient + direct * max(dot(n, toLight), 0.0));
    vec3 camera = frame.cameraPosition_time.xyz;
    float distance_m = distance(vWorld_m, camera);
    // What the near blades leave undrawn of the field, the far field draws.
    float farShare = 1.0 - keptFraction(distance_m, tiling);
    vec3 color = soil;
    if (uFarField && farShare > 0.001) {
        vec3 ray = normalize(vWorld_m - camera);
        float descent = max(-ray.y, 0.02);
        // Back from the ground point to where the ray enters the grass layer.
        float inLayer_m = uSliceHeight_m / descent;
        vec3 entry = vWorld_m - ray * inLayer_m;
        float density = terrainDensityAt(vWorld_m.xz, tiling) * farShare;
        float lod = log2(max(distance_m * uPixelSize_perM / (tiling.tile.x / 512.0), 1.0));
        float bladeLight = frame.lightDirection.w * mix(0.6, 1.0, shadow);
        // Where neighbouring slice planes are under a few pixels apart their crossings alias
        // into moire; there the layer is drawn as its averages: the ray's crossings shared out
        // over the bands of height it passes, top first, each band's coverage per crossing.
        float spacing_px = uSliceSpacing_m / max(distance_m * uPixelSize_perM, 1e-6);
        float traced = smoothstep(1.5, 4.0, spacing_px);
        float crossingsPerBand =
            inLayer_m * (abs(ray.x) + abs(ray.z)) / uSliceSpacing_m / float(HEIGHT_BANDS);
        vec3 averageGrass = vec3(0.0);
        float averageCover = 0.0;
        for (int b = HEIGHT_BANDS - 1; traced < 1.0 && b >= 0; --b) {
            float alpha = 1.0 - pow(1.0 - min(uBandCoverage[b] * density, 0.999), crossingsPerBand);
            averageGrass += (1.0 - averageCover) * alpha * litBlade(uBandAlbedo[b], bladeLight);
            averageCover += (1.0 - averageCover) * alpha;
        }
        vec3 grass = vec3(0.0);
        float cover = 0.0;
        // Walk the two families of planes (constant z, constant x) in order along the ray.
        vec2 stepDir = vec2(ray.z, ray.x);
        vec2 next = vec2(1e9);
        vec2 dt = vec2(1e9);
        for (int a = 0; a < 2; ++a) {
            float c = a == 0 ? entry.z : entry.x;
            float r = stepDir[a];
            if (abs(r) > 1e-5) {
                float plane = (r > 0.0 ? floor(c / uSliceSpacing_m) + 1.0 : ceil(c / uSliceSpacing_m) - 1.0) * uSliceSpacing_m;
                next[a] = (plane - c) / r;
                dt[a] = uSliceSpacing_m / abs(r);
            }
        }
        int crossings = 0;
        float walked_m = 0.0;
        for (; traced > 0.0 && crossings < MAX_SLICE_CROSSINGS && cover < 0.95; ++crossings) {
            int a = next.x < next.y ? 0 : 1;
            float t = next[a];
            if (t > inLayer_m) break;
            next[a] += dt[a];
            walked_m = t;
            vec3 q = entry + ray * t;
            float height = uSliceHeight_m - t * descent;  // above the ground, flat locally
            float along = a == 0 ? q.x : q.z;
            float across = a == 0 ? q.z : q.x;
            float repeat = floor(along / tiling.tile.x);
            int slab = int(mod(floor(across / uSliceSpacing_m) + repeat * 7.0, float(uSlicesPerAxis)));
            vec3 uvw = vec3(along / tiling.tile.x, height / uSliceHeight_m, float(a * uSlicesPerAxis + slab));
            vec4 texel = textureLod(slices, uvw, lod);
            float alpha = texel.a * density;
            vec3 albedo = displayToLinear(texel.rgb / max(texel.a, 1e-3));
            grass += (1.0 - cover) * alpha * litBlade(albedo, bladeLight);
            cover += (1.0 - cover) * alpha;
        }
        // Cut short at a grazing angle: the rest of the layer is more of the same grass.
        if (crossings == MAX_SLICE_CROSSINGS && cover > 0.0 && cover < 0.95) {
            // The layer left behind transmits as much per metre as the part walked.
            float rest = 1.0 - pow(1.0 - cover, (inLayer_m - walked_m) / max(walked_m, 1e-3));
            grass *= (cover + (1.0 - cover) * rest) / cover;
            cover = cover + (1.0 - cover) * rest;
        }
        grass = mix(averageGrass, grass, traced);
        cover = mix(averageCover, cover, traced);
        color = grass + (1.0 - cover) * soil;
    }
    fragColor = vec4(linearToDisplay(withAerialPerspective(color, vWorld_m, frame)), 1.0);
}
