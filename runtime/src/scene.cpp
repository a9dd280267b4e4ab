// Scene file reader (format "meadow.scene", version 1).
#include "meadow/runtime/scene.h"

#include <cmath>
#include <glm/common.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "default_archetypes.h"
#include "ground_maps.h"
#include "meadow/core/json_reader.h"
#include "meadow/modeling/archetype_library.h"
#include "meadow/runtime/error.h"
#include "short_number.h"

namespace meadow::runtime {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr int kMaxImageSide_px = 16384;  // GL_MAX_RENDERBUFFER_SIZE of current drivers

// A file named by the scene, relative to the scene file's folder; it must exist.
fs::path sceneFilePath(const JsonReader& r, std::string_view key, const fs::path& origin) {
    fs::path p = r.string(key);
    if (p.is_relative()) p = origin.parent_path() / p;
    std::error_code ec;
    if (!fs::exists(p, ec)) r.fail(key, "file " + p.string() + " does not exist");
    return p;
}

// Scenes are metres across a meadow, up to a landscape: a position farther out is a unit or
// typing mistake (and single-precision positions that far apart are millimetres coarse).
constexpr float kMaxSceneExtent_m = 1e5f;

glm::vec3 position(const JsonReader& r, std::string_view key, glm::vec3 fallback) {
    const glm::vec3 p = r.vec3(key, fallback);
    for (int i = 0; i < 3; ++i)
        if (std::abs(p[i]) > kMaxSceneExtent_m)
            r.fail(key, "lies " + shortNumber(std::abs(p[i])) + " m from the origin, beyond " +
                            shortNumber(kMaxSceneExtent_m) + " m: positions are in metres");
    return p;
}

glm::vec3 normalised(const JsonReader& r, std::string_view key, glm::vec3 fallback) {
    const glm::vec3 v = r.vec3(key, fallback);
    const float n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (!(n > 0.f)) r.fail(key, "a direction must not be zero");
    return v / n;
}

// An optional section: an empty object when absent.
JsonReader section(const JsonReader& root, std::string_view key) {
    static const json kEmpty = json::object();
    return root.has(key) ? root.object(key) : JsonReader(kEmpty, std::string(key));
}

// `{ "image": PNG, "min_xz_m": [x, z], "max_xz_m": [x, z] }`, the form of every ground map.
GroundImage readGroundImage(const JsonReader& d, const fs::path& origin) {
    d.onlyKeys({"image", "min_xz_m", "max_xz_m"});
    GroundImage map;
    map.image = sceneFilePath(d, "image", origin);
    const auto xz = [&](std::string_view key) {
        const json& v = d.at(key);
        if (!v.is_array() || v.size() != 2) d.fail(key, "expected [x, z] in metres");
        return glm::vec2(finiteFloat(v[0], elementPath(d.pathOf(key), 0)),
                         finiteFloat(v[1], elementPath(d.pathOf(key), 1)));
    };
    map.minXZ_m = xz("min_xz_m");
    map.maxXZ_m = xz("max_xz_m");
    if (!(map.maxXZ_m.x > map.minXZ_m.x && map.maxXZ_m.y > map.minXZ_m.y))
        d.fail("", "max_xz_m must be greater than min_xz_m in x and z");
    return map;
}

std::vector<SceneMesh> readMeshes(const JsonReader& root, std::string_view key,
                                  glm::vec3 defaultAlbedo, const fs::path& origin) {
    std::vector<SceneMesh> meshes;
    if (!root.has(key)) return meshes;
    const json& list = root.array(key);
    for (std::size_t i = 0; i < list.size(); ++i) {
        const JsonReader m(list[i], elementPath(root.pathOf(key), i));
        m.onlyKeys({"gltf", "albedo"});
        meshes.push_back({sceneFilePath(m, "gltf", origin), m.vec3("albedo", defaultAlbedo)});
    }
    return meshes;
}

void readArchetypes(const JsonReader& root, SceneDescription& scene, const fs::path& origin) {
    static const json kNoWeights = json::object();
    const JsonReader a = section(root, "archetypes");
    a.onlyKeys({"library", "weights", "map"});
    if (!root.has("archetypes") || (a.has("library") && a.at("library") == "default")) {
        scene.archetypes = defaultArchetypes();
    } else {
        const fs::path library = sceneFilePath(a, "library", origin);
        try {
            scene.archetypes = modeling::loadArchetypeLibrary(library).archetypes;
        } catch (const Error& e) {
            a.fail("library", e.what());
        }
    }
    const JsonReader weights =
        a.has("weights") ? a.object("weights") : JsonReader(kNoWeights, a.pathOf("weights"));
    if (scene.archetypes.empty()) a.fail("", "the archetype set is empty");
    std::set<std::string> names;
    for (const auto& arch : scene.archetypes) names.insert(arch.name);
    for (const auto& [name, w] : weights.node().items())
        if (!names.count(name)) weights.fail(name, "no archetype of that name");
    for (const auto& arch : scene.archetypes)
        scene.archetypeWeights.push_back(weights.floatNumber(arch.name, 1.f, 0.f, 1e6f));
    float total = 0.f;
    for (float w : scene.archetypeWeights) total += w;
    if (!(total > 0.f)) weights.fail("", "at least one weight must be positive");
    for (const auto& arch : scene.archetypes)
        if (!(arch.height_m() > 0.f) || arch.width.width_m.size() < 2 ||
            !(arch.width.maxWidth_m() > 0.f))
            a.fail("", "archetype '" + arch.name + "' has no height or no width");
    // The map is read here as well as when the blades are seeded, so a bad map fails on load,
    // before any GL context exists, with the scene file and the field in the message.
    if (a.has("map")) {
        const JsonReader m = a.object("map");
        const ArchetypeMap map = readGroundImage(m, origin);
        const ArchetypeMapImage image = readArchetypeMap(map, scene.archetypes.size());
        if (!image.problem.empty()) m.fail("image", image.problem);
        scene.archetypeMap = map;
    }
}

void readBlades(const JsonReader& b, BladeSeeding& s, const fs::path& origin) {
    b.onlyKeys({"density_per_m2", "tuft_fraction", "tuft_blades", "tuft_radius_m", "tuft_spacing_m",
                "height_scale", "width_scale", "stiffness", "seed", "density_map"});
    s.density_per_m2 = b.floatNumber("density_per_m2", s.density_per_m2, 0.f, 1e5f);
    s.tuftFraction = b.floatNumber("tuft_fraction", s.tuftFraction, 0.f, 1.f);
    const glm::vec2 tuftBlades = b.range(
        "tuft_blades", {static_cast<float>(s.tuftBladesMin), static_cast<float>(s.tuftBladesMax)},
        1.f, 1000.f);
    s.tuftBladesMin = static_cast<int>(tuftBlades.x);
    s.tuftBladesMax = static_cast<int>(tuftBlades.y);
    s.tuftRadius_m = b.floatNumber("tuft_radius_m", s.tuftRadius_m, 0.f, 10.f);
    s.tuftSpacing_m = b.floatNumber("tuft_spacing_m", s.tuftSpacing_m, 0.f, 100.f);
    s.heightScale = b.range("height_scale", s.heightScale, 0.01f, 100.f);
    s.widthScale = b.range("width_scale", s.widthScale, 0.01f, 100.f);
    s.stiffness = b.range("stiffness", s.stiffness, 0.f, 100.f);
    s.seed = static_cast<std::uint32_t>(
        b.integer("seed", static_cast<int>(s.seed), 0, std::numeric_limits<int>::max()));
    if (b.has("density_map")) {
        const JsonReader m = b.object("density_map");
        s.densityMap = readGroundImage(m, origin);
        // Read on load as well as when seeding, as archetypes.map is: a bad image fails before
        // any GL context exists, with the scene file and the field in the message.
        if (const std::string why = densityMapProblem(*s.densityMap); !why.empty())
            m.fail("image", why);
    }
}

void readCamera(const JsonReader& c, CameraDescription& cam) {
    c.onlyKeys({"position_m", "target_m", "path", "vertical_fov_deg", "near_m", "far_m"});
    cam.verticalFov_deg = c.floatNumber("vertical_fov_deg", cam.verticalFov_deg, 1.f, 170.f);
    cam.near_m = c.floatNumber("near_m", cam.near_m, 1e-4f, 1e4f);
    cam.far_m = c.floatNumber("far_m", cam.far_m, 1e-3f, 1e6f);
    if (!(cam.far_m > cam.near_m)) c.fail("far_m", "must be greater than near_m");
    if (c.has("path")) {
        if (c.has("position_m") || c.has("target_m"))
            c.fail("", "give either position_m/target_m or path, not both");
        const json& path = c.array("path");
        if (path.empty()) c.fail("path", "expected a non-empty array");
        for (std::size_t i = 0; i < path.size(); ++i) {
            const JsonReader k(path[i], elementPath(c.pathOf("path"), i));
            k.onlyKeys({"time_s", "position_m", "target_m"});
            CameraKey key{k.floatNumber("time_s", 0.f, 0.f, 1e6f), position(k, "position_m", {}),
                          position(k, "target_m", {})};
            if (!cam.path.empty() && !(key.time_s > cam.path.back().time_s))
                k.fail("time_s", "keys must be in increasing time");
            cam.path.push_back(key);
        }
    } else {
        const CameraKey fallback;
        cam.path.push_back({0.f, position(c, "position_m", fallback.position_m),
                            position(c, "target_m", fallback.target_m)});
    }
    for (const CameraKey& k : cam.path)
        if (k.position_m == k.target_m) c.fail("", "position_m and target_m must differ");
}

void readLight(const JsonReader& l, LightDescription& light) {
    l.onlyKeys(
        {"direction", "intensity", "ambient", "sky_color", "zenith_color", "fog_distance_m"});
    light.direction = normalised(l, "direction", light.direction);
    light.intensity = l.floatNumber("intensity", light.intensity, 0.f, 100.f);
    light.ambient = l.floatNumber("ambient", light.ambient, 0.f, 10.f);
    light.skyColor = l.vec3("sky_color", light.skyColor);
    if (l.has("zenith_color")) light.zenithColor = l.vec3("zenith_color", light.skyColor);
    light.fogDistance_m = l.floatNumber("fog_distance_m", light.fogDistance_m, 0.f, 1e6f);
}

void readShadows(const JsonReader& s, ShadowDescription& sh) {
    s.onlyKeys({"enabled", "map_size_px", "distance_m", "strength"});
    sh.enabled = s.boolean("enabled", sh.enabled);
    sh.mapSize_px = s.integer("map_size_px", sh.mapSize_px, 64, 8192);
    sh.distance_m = s.floatNumber("distance_m", sh.distance_m, 0.1f, 1e4f);
    sh.strength = s.floatNumber("strength", sh.strength, 0.f, 1.f);
}

// A height field this many samples a side at most (16-bit-free R32F texture, 64 MiB).
constexpr int kMaxTerrainSamples = 4097;

TerrainDescription readTerrain(const JsonReader& t) {
    t.onlyKeys({"min_xz_m", "max_xz_m", "samples", "relief_m", "feature_size_m", "seed", "albedo",
                "relative_heights"});
    TerrainDescription d;
    const auto xz = [&](std::string_view key, glm::vec2 fallback) {
        if (!t.has(key)) return fallback;
        const json& v = t.at(key);
        if (!v.is_array() || v.size() != 2) t.fail(key, "expected [x, z] in metres");
        const glm::vec2 p(finiteFloat(v[0], elementPath(t.pathOf(key), 0)),
                          finiteFloat(v[1], elementPath(t.pathOf(key), 1)));
        if (std::abs(p.x) > kMaxSceneExtent_m || std::abs(p.y) > kMaxSceneExtent_m)
            t.fail(key, "lies beyond " + shortNumber(kMaxSceneExtent_m) +
                            " m from the origin: positions are in metres");
        return p;
    };
    d.minXZ_m = xz("min_xz_m", d.minXZ_m);
    d.maxXZ_m = xz("max_xz_m", d.maxXZ_m);
    if (!(d.maxXZ_m.x > d.minXZ_m.x && d.maxXZ_m.y > d.minXZ_m.y))
        t.fail("", "max_xz_m must be greater than min_xz_m in x and z");
    d.samples = t.integer("samples", d.samples, 2, kMaxTerrainSamples);
    d.relief_m = t.floatNumber("relief_m", d.relief_m, 0.f, 1e4f);
    d.featureSize_m = t.floatNumber("feature_size_m", d.featureSize_m, 1e-2f, 1e6f);
    d.seed = static_cast<std::uint32_t>(
        t.integer("seed", static_cast<int>(d.seed), 0, std::numeric_limits<int>::max()));
    d.albedo = t.vec3("albedo", d.albedo);
    d.relativeHeights = t.boolean("relative_heights", d.relativeHeights);
    return d;
}

TilingDescription readTiling(const JsonReader& t) {
    t.onlyKeys({"tile_size_m", "near_distance_m", "transition_m", "full_density_distance_m",
                "active_distance_m", "pool_tiles", "max_drawn_blades", "far_field"});
    TilingDescription d;
    d.tileSize_m = t.floatNumber("tile_size_m", d.tileSize_m, 0.25f, 100.f);
    d.nearDistance_m = t.floatNumber("near_distance_m", d.nearDistance_m, 0.f, 1e4f);
    d.transition_m = t.floatNumber("transition_m", d.transition_m, 0.f, 1e4f);
    if (d.transition_m > d.nearDistance_m)
        t.fail("transition_m",
               "must not exceed near_distance_m (" + shortNumber(d.nearDistance_m) + " m)");
    d.fullDensityDistance_m =
        t.floatNumber("full_density_distance_m", d.fullDensityDistance_m, 0.1f, 1e4f);
    d.activeDistance_m = t.floatNumber("active_distance_m", d.activeDistance_m, 0.f, 1e3f);
    d.poolTiles = t.integer("pool_tiles", d.poolTiles, 0, 65536);
    d.maxDrawnBlades = t.integer("max_drawn_blades", d.maxDrawnBlades, 64, 1 << 26);
    d.farField = t.boolean("far_field", d.farField);
    return d;
}

void readWind(const JsonReader& w, WindDescription& wind) {
    // The field was named as an acceleration but always fed the wave amplitude (m/s).
    if (w.has("strength_m_s2"))
        w.fail("strength_m_s2",
               "renamed to wave_amplitude_m_s (the wind pushes the tip with a velocity, m/s); "
               "rename the field, its value keeps its meaning");
    w.onlyKeys({"direction", "wave_amplitude_m_s", "wavelength_m", "frequency_hz", "source_m",
                "source_amplitude_m_s", "source_radius_m", "gust_amplitude_m_s", "gust_size_m",
                "gust_speed_m_s", "turbulence_amplitude_m_s", "turbulence_size_m"});
    wind.direction = normalised(w, "direction", wind.direction);
    wind.waveAmplitude_m_s =
        w.floatNumber("wave_amplitude_m_s", wind.waveAmplitude_m_s, 0.f, 1000.f);
    wind.wavelength_m = w.floatNumber("wavelength_m", wind.wavelength_m, 1e-3f, 1e6f);
    wind.frequency_hz = w.floatNumber("frequency_hz", wind.frequency_hz, 0.f, 100.f);
    wind.source_m = position(w, "source_m", wind.source_m);
    wind.sourceAmplitude_m_s =
        w.floatNumber("source_amplitude_m_s", wind.sourceAmplitude_m_s, 0.f, 1000.f);
    wind.sourceRadius_m = w.floatNumber("source_radius_m", wind.sourceRadius_m, 1e-3f, 1e6f);
    wind.gustAmplitude_m_s =
        w.floatNumber("gust_amplitude_m_s", wind.gustAmplitude_m_s, 0.f, 1000.f);
    wind.gustSize_m = w.floatNumber("gust_size_m", wind.gustSize_m, 1e-2f, 1e5f);
    wind.gustSpeed_m_s = w.floatNumber("gust_speed_m_s", wind.gustSpeed_m_s, 0.f, 1000.f);
    wind.turbulenceAmplitude_m_s =
        w.floatNumber("turbulence_amplitude_m_s", wind.turbulenceAmplitude_m_s, 0.f, 1000.f);
    wind.turbulenceSize_m = w.floatNumber("turbulence_size_m", wind.turbulenceSize_m, 1e-2f, 1e5f);
}

// A mesh collider's spheres: at most this many (each costs every blade a test each step).
constexpr int kMaxColliderSpheres = 256;

void readColliders(const JsonReader& root, std::vector<ColliderDescription>& colliders,
                   const fs::path& origin) {
    if (!root.has("colliders")) return;
    const json& list = root.array("colliders");
    for (std::size_t i = 0; i < list.size(); ++i) {
        const JsonReader k(list[i], elementPath("colliders", i));
        k.onlyKeys({"center_m", "radius_m", "velocity_m_s", "path", "gltf", "spheres", "visible",
                    "albedo"});
        ColliderDescription c;
        c.center_m = position(k, "center_m", {});
        if (k.has("gltf")) {
            if (k.has("radius_m"))
                k.fail("radius_m",
                       "belongs to a sphere collider; a mesh collider's size is its mesh");
            c.gltf = sceneFilePath(k, "gltf", origin);
            c.maxSpheres = k.integer("spheres", c.maxSpheres, 1, kMaxColliderSpheres);
        } else {
            if (k.has("spheres")) k.fail("spheres", "belongs to a mesh collider (with gltf)");
            c.radius_m = k.floatNumber("radius_m", c.radius_m, 1e-4f, 1e4f);
        }
        if (k.has("path")) {
            if (k.has("velocity_m_s") || k.has("center_m"))
                k.fail("path", "give either center_m/velocity_m_s or path, not both");
            const json& path = k.array("path");
            if (path.empty()) k.fail("path", "expected a non-empty array");
            for (std::size_t j = 0; j < path.size(); ++j) {
                const JsonReader key(path[j], elementPath(k.pathOf("path"), j));
                key.onlyKeys({"time_s", "position_m"});
                const ColliderKey ck{key.floatNumber("time_s", 0.f, 0.f, 1e6f),
                                     position(key, "position_m", {})};
                if (!c.path.empty() && !(ck.time_s > c.path.back().time_s))
                    key.fail("time_s", "keys must be in increasing time");
                c.path.push_back(ck);
            }
            c.center_m = c.path.front().position_m;
        } else {
            c.velocity_m_s = k.vec3("velocity_m_s", {});
        }
        c.visible = k.boolean("visible", c.visible);
        c.albedo = k.vec3("albedo", c.albedo);
        colliders.push_back(std::move(c));
    }
}

void readPhysics(const JsonReader& p, PhysicsDescription& ph) {
    p.onlyKeys({"enabled", "gravity_direction", "gravity_m_s2", "gravity_center_m",
                "gravity_center_m_s2", "gravity_center_mix", "collision_decay_per_s"});
    ph.enabled = p.boolean("enabled", ph.enabled);
    ph.gravityDirection = normalised(p, "gravity_direction", ph.gravityDirection);
    ph.gravity_m_s2 = p.floatNumber("gravity_m_s2", ph.gravity_m_s2, 0.f, 1000.f);
    ph.gravityCenter_m = p.vec3("gravity_center_m", ph.gravityCenter_m);
    ph.gravityCenter_m_s2 =
        p.floatNumber("gravity_center_m_s2", ph.gravityCenter_m_s2, 0.f, 1000.f);
    ph.gravityCenterMix = p.floatNumber("gravity_center_mix", ph.gravityCenterMix, 0.f, 1.f);
    ph.collisionDecay_per_s =
        p.floatNumber("collision_decay_per_s", ph.collisionDecay_per_s, 0.f, 1000.f);
}

void readCulling(const JsonReader& k, CullingDescription& cull) {
    k.onlyKeys({"orientation", "frustum", "distance", "occlusion", "orientation_threshold",
                "max_distance_m", "distance_levels"});
    cull.orientation = k.boolean("orientation", cull.orientation);
    cull.frustum = k.boolean("frustum", cull.frustum);
    cull.distance = k.boolean("distance", cull.distance);
    cull.occlusion = k.boolean("occlusion", cull.occlusion);
    cull.orientationThreshold =
        k.floatNumber("orientation_threshold", cull.orientationThreshold, 0.f, 1.f);
    cull.maxDistance_m = k.floatNumber("max_distance_m", cull.maxDistance_m, 0.f, 1e6f);
    cull.distanceLevels = k.integer("distance_levels", cull.distanceLevels, 1, 1000);
}

void readRender(const JsonReader& v, RenderSettings& rs) {
    v.onlyKeys({"size_px", "msaa_samples", "frame_rate_hz", "patch_size", "shape", "displacement",
                "max_tess_level", "min_width_px", "root_color", "tip_color", "translucency",
                "ao_at_root"});
    if (v.has("size_px")) {
        const json& size = v.at("size_px");
        if (!size.is_array() || size.size() != 2 || !size[0].is_number_integer() ||
            !size[1].is_number_integer() || size[0].get<long long>() < 1 ||
            size[1].get<long long>() < 1 || size[0].get<long long>() > kMaxImageSide_px ||
            size[1].get<long long>() > kMaxImageSide_px)
            v.fail("size_px", "expected [width, height] in pixels, each 1.." +
                                  std::to_string(kMaxImageSide_px));
        rs.width_px = size[0].get<int>();
        rs.height_px = size[1].get<int>();
    }
    rs.msaaSamples = v.integer("msaa_samples", rs.msaaSamples, 1, 16);
    rs.frameRate_hz = v.floatNumber("frame_rate_hz", rs.frameRate_hz, 1e-3f, 1e4f);
    rs.patchSize = v.integer("patch_size", rs.patchSize, 1, 1 << 20);
    if (v.has("shape")) {
        const std::string shape = v.string("shape");
        if (shape == "archetype") {
            rs.shapeOverride = -1;
        } else if (const auto s = modeling::kAnalyticShapeNames.parse(shape)) {
            rs.shapeOverride = static_cast<int>(*s);
        } else {
            v.fail("shape",
                   "expected \"archetype\" or one of " + modeling::kAnalyticShapeNames.list());
        }
    }
    rs.displacement = v.boolean("displacement", rs.displacement);
    rs.maxTessLevel = v.floatNumber("max_tess_level", rs.maxTessLevel, 1.f, 64.f);
    rs.minWidth_px = v.floatNumber("min_width_px", rs.minWidth_px, 0.f, 100.f);
    rs.rootColor = v.vec3("root_color", rs.rootColor);
    rs.tipColor = v.vec3("tip_color", rs.tipColor);
    rs.translucency = v.floatNumber("translucency", rs.translucency, 0.f, 1.f);
    rs.aoAtRoot = v.floatNumber("ao_at_root", rs.aoAtRoot, 0.f, 1.f);
}

}  // namespace

glm::vec3 ColliderDescription::positionAt(float time_s) const {
    if (path.empty()) return center_m + velocity_m_s * time_s;
    if (time_s <= path.front().time_s) return path.front().position_m;
    for (std::size_t i = 1; i < path.size(); ++i)
        if (time_s <= path[i].time_s) {
            const float f = (time_s - path[i - 1].time_s) / (path[i].time_s - path[i - 1].time_s);
            return glm::mix(path[i - 1].position_m, path[i].position_m, f);
        }
    return path.back().position_m;
}

SceneDescription parseSceneDescription(const std::string& jsonText, const fs::path& origin) {
    SceneDescription scene;
    scene.file = origin;
    try {
        const json doc = parseJsonObject(jsonText);
        const JsonReader root(doc);
        checkJsonFormat(doc, {kSceneFormat, kSceneVersion});
        root.onlyKeys({"format", "version", "grass", "props", "archetypes", "blades", "camera",
                       "light", "wind", "colliders", "physics", "culling", "shadows", "render",
                       "terrain", "tiling"});
        scene.grassMeshes = readMeshes(root, "grass", SceneMesh{}.albedo, origin);
        if (root.has("terrain")) scene.terrain = readTerrain(root.object("terrain"));
        if (root.has("tiling")) {
            if (!scene.terrain)
                root.fail("tiling", "tiles are laid over a terrain: add a \"terrain\" section");
            if (!scene.grassMeshes.empty())
                root.fail("grass", "a tiled scene grows its grass on the terrain; drop \"grass\"");
            scene.tiling = readTiling(root.object("tiling"));
        } else if (scene.terrain) {
            root.fail("terrain", "a terrain is grown with tiles: add a \"tiling\" section");
        } else if (scene.grassMeshes.empty()) {
            root.fail("grass", "name at least one mesh to grow grass on (or a terrain and tiling)");
        }
        scene.props = readMeshes(root, "props", {0.4f, 0.38f, 0.35f}, origin);
        readArchetypes(root, scene, origin);
        readBlades(section(root, "blades"), scene.blades, origin);
        readCamera(section(root, "camera"), scene.camera);
        readLight(section(root, "light"), scene.light);
        readWind(section(root, "wind"), scene.wind);
        readColliders(root, scene.colliders, origin);
        readPhysics(section(root, "physics"), scene.physics);
        readCulling(section(root, "culling"), scene.culling);
        readShadows(section(root, "shadows"), scene.shadows);
        readRender(section(root, "render"), scene.render);
    } catch (const JsonError& e) {
        throw RuntimeError(origin.string() + ": " + e.what() +
                           "; fix the scene file (docs/formats.md, \"Scene\")");
    }
    return scene;
}

SceneDescription loadSceneDescription(const fs::path& sceneFile) {
    std::string text;
    try {
        text = readTextFile(sceneFile);
    } catch (const Error& e) {
        throw RuntimeError("cannot read scene file: " + std::string(e.what()) + "; check the path");
    }
    return parseSceneDescription(text, sceneFile);
}

}  // namespace meadow::runtime
