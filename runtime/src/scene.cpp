// Scene file reader (format "meadow.scene", version 1).
#include "meadow/runtime/scene.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "default_archetypes.h"
#include "ground_maps.h"
#include "meadow/modeling/archetype_library.h"
#include "meadow/runtime/error.h"
#include "short_number.h"

namespace meadow::runtime {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr int kMaxImageSide_px = 16384;  // GL_MAX_RENDERBUFFER_SIZE of current drivers

// Every field read goes through one reader so each error names the file and the JSON path.
class Reader {
public:
    explicit Reader(fs::path origin) : origin_(std::move(origin)) {}

    [[noreturn]] void fail(const std::string& where, const std::string& what) const {
        throw RuntimeError(origin_.string() + ": " + where + ": " + what +
                           "; fix the scene file (README, \"Scene format\")");
    }

    // Rejects keys the format does not define: a typo must not silently fall back to a default.
    void onlyKeys(const json& j, const std::string& where, std::set<std::string> allowed) const {
        if (!j.is_object()) fail(where, "expected a JSON object");
        for (const auto& [key, value] : j.items())
            if (!allowed.count(key)) fail(where + "." + key, "unknown field");
    }

    float number(const json& j, const std::string& key, const std::string& where, float fallback,
                 float min, float max) const {
        if (!j.contains(key)) return fallback;
        const json& v = j.at(key);
        if (!v.is_number()) fail(where + "." + key, "expected a number");
        const double d = v.get<double>();
        if (!std::isfinite(d) || d < min || d > max)
            fail(where + "." + key, "value " + v.dump() + " outside [" + shortNumber(min) + ", " +
                                        shortNumber(max) + "]");
        return static_cast<float>(d);
    }

    int integer(const json& j, const std::string& key, const std::string& where, int fallback,
                int min, int max) const {
        if (!j.contains(key)) return fallback;
        const json& v = j.at(key);
        if (!v.is_number_integer()) fail(where + "." + key, "expected an integer");
        const long long n = v.get<long long>();
        if (n < min || n > max)
            fail(where + "." + key, "value " + v.dump() + " outside [" + shortNumber(min) + ", " +
                                        shortNumber(max) + "]");
        return static_cast<int>(n);
    }

    bool boolean(const json& j, const std::string& key, const std::string& where,
                 bool fallback) const {
        if (!j.contains(key)) return fallback;
        if (!j.at(key).is_boolean()) fail(where + "." + key, "expected true or false");
        return j.at(key).get<bool>();
    }

    glm::vec3 vec3(const json& j, const std::string& key, const std::string& where,
                   glm::vec3 fallback) const {
        if (!j.contains(key)) return fallback;
        const json& v = j.at(key);
        if (!v.is_array() || v.size() != 3) fail(where + "." + key, "expected [x, y, z]");
        glm::vec3 r;
        for (int i = 0; i < 3; ++i) {
            if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
                fail(where + "." + key, "expected three finite numbers");
            r[i] = v[i].get<float>();
        }
        return r;
    }

    // A [min, max] range with min <= max inside [lo, hi].
    glm::vec2 range(const json& j, const std::string& key, const std::string& where,
                    glm::vec2 fallback, float lo, float hi) const {
        if (!j.contains(key)) return fallback;
        const json& v = j.at(key);
        if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
            fail(where + "." + key, "expected [min, max]");
        const glm::vec2 r{v[0].get<float>(), v[1].get<float>()};
        if (!(r.x <= r.y) || r.x < lo || r.y > hi)
            fail(where + "." + key, "expected min <= max within [" + shortNumber(lo) + ", " +
                                        shortNumber(hi) + "], got " + v.dump());
        return r;
    }

    fs::path path(const json& j, const std::string& key, const std::string& where) const {
        if (!j.contains(key) || !j.at(key).is_string())
            fail(where + "." + key, "expected a file name");
        fs::path p = j.at(key).get<std::string>();
        if (p.is_relative()) p = origin_.parent_path() / p;
        if (!fs::exists(p)) fail(where + "." + key, "file " + p.string() + " does not exist");
        return p;
    }

    const fs::path& origin() const { return origin_; }

private:
    fs::path origin_;
};

glm::vec3 normalised(const Reader& r, glm::vec3 v, const std::string& where) {
    const float n = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (!(n > 0.f)) r.fail(where, "a direction must not be zero");
    return v / n;
}

// `{ "image": PNG, "min_xz_m": [x, z], "max_xz_m": [x, z] }`, the form of every ground map.
GroundImage readGroundImage(const Reader& r, const json& d, const std::string& where) {
    r.onlyKeys(d, where, {"image", "min_xz_m", "max_xz_m"});
    GroundImage map;
    map.image = r.path(d, "image", where);
    auto xz = [&](const char* key) {
        const json* v = d.contains(key) ? &d.at(key) : nullptr;
        if (!v || !v->is_array() || v->size() != 2 || !(*v)[0].is_number() ||
            !(*v)[1].is_number() || !std::isfinite((*v)[0].get<double>()) ||
            !std::isfinite((*v)[1].get<double>()))
            r.fail(where + "." + key, "expected [x, z] in metres");
        return glm::vec2((*v)[0].get<float>(), (*v)[1].get<float>());
    };
    map.minXZ_m = xz("min_xz_m");
    map.maxXZ_m = xz("max_xz_m");
    if (!(map.maxXZ_m.x > map.minXZ_m.x && map.maxXZ_m.y > map.minXZ_m.y))
        r.fail(where, "max_xz_m must be greater than min_xz_m in x and z");
    return map;
}

std::vector<SceneMesh> readMeshes(const Reader& r, const json& root, const std::string& key,
                                  glm::vec3 defaultAlbedo) {
    std::vector<SceneMesh> meshes;
    if (!root.contains(key)) return meshes;
    if (!root.at(key).is_array()) r.fail(key, "expected an array of meshes");
    for (std::size_t i = 0; i < root.at(key).size(); ++i) {
        const json& m = root.at(key)[i];
        const std::string where = key + "[" + std::to_string(i) + "]";
        r.onlyKeys(m, where, {"gltf", "albedo"});
        meshes.push_back({r.path(m, "gltf", where), r.vec3(m, "albedo", where, defaultAlbedo)});
    }
    return meshes;
}

void readArchetypes(const Reader& r, const json& root, SceneDescription& scene) {
    json weights = json::object();
    if (!root.contains("archetypes")) {
        scene.archetypes = defaultArchetypes();
    } else {
        const json& a = root.at("archetypes");
        r.onlyKeys(a, "archetypes", {"library", "weights", "map"});
        if (a.contains("library") && a.at("library") == "default") {
            scene.archetypes = defaultArchetypes();
        } else {
            const fs::path library = r.path(a, "library", "archetypes");
            try {
                scene.archetypes = modeling::loadArchetypeLibrary(library).archetypes;
            } catch (const Error& e) {
                r.fail("archetypes.library", e.what());
            }
        }
        if (a.contains("weights")) weights = a.at("weights");
        if (!weights.is_object())
            r.fail("archetypes.weights", "expected {\"archetype name\": weight}");
    }
    if (scene.archetypes.empty()) r.fail("archetypes", "the archetype set is empty");
    std::set<std::string> names;
    for (const auto& arch : scene.archetypes) names.insert(arch.name);
    for (const auto& [name, w] : weights.items())
        if (!names.count(name)) r.fail("archetypes.weights." + name, "no archetype of that name");
    for (const auto& arch : scene.archetypes)
        scene.archetypeWeights.push_back(
            r.number(weights, arch.name, "archetypes.weights", 1.f, 0.f, 1e6f));
    float total = 0.f;
    for (float w : scene.archetypeWeights) total += w;
    if (!(total > 0.f)) r.fail("archetypes.weights", "at least one weight must be positive");
    for (const auto& arch : scene.archetypes)
        if (!(arch.height_m() > 0.f) || arch.width.width_m.size() < 2 ||
            !(arch.width.maxWidth_m() > 0.f))
            r.fail("archetypes", "archetype '" + arch.name + "' has no height or no width");
    // The map is read here as well as when the blades are seeded, so a bad map fails on load,
    // before any GL context exists, with the scene file and the field in the message.
    if (root.contains("archetypes") && root.at("archetypes").contains("map")) {
        const ArchetypeMap map =
            readGroundImage(r, root.at("archetypes").at("map"), "archetypes.map");
        const ArchetypeMapImage image = readArchetypeMap(map, scene.archetypes.size());
        if (!image.problem.empty()) r.fail("archetypes.map.image", image.problem);
        scene.archetypeMap = map;
    }
}

}  // namespace

SceneDescription parseSceneDescription(const std::string& jsonText, const fs::path& origin) {
    const Reader r(origin);
    json root;
    try {
        root = json::parse(jsonText);
    } catch (const json::parse_error& e) {
        r.fail("file", std::string("not valid JSON (") + e.what() + ")");
    }
    r.onlyKeys(root, "scene",
               {"format", "version", "grass", "props", "archetypes", "blades", "camera", "light",
                "wind", "colliders", "physics", "culling", "render"});
    if (!root.contains("format") || root.at("format") != kSceneFormat)
        r.fail("format", std::string("expected \"") + kSceneFormat + "\"");
    if (!root.contains("version") || !root.at("version").is_number_integer())
        r.fail("version", "missing");
    if (root.at("version").get<int>() != kSceneVersion)
        r.fail("version", "version " + root.at("version").dump() +
                              " is not supported (this meadow reads " +
                              std::to_string(kSceneVersion) + ")");

    SceneDescription scene;
    scene.file = origin;
    scene.grassMeshes = readMeshes(r, root, "grass", SceneMesh{}.albedo);
    if (scene.grassMeshes.empty()) r.fail("grass", "name at least one mesh to grow grass on");
    scene.props = readMeshes(r, root, "props", {0.4f, 0.38f, 0.35f});
    readArchetypes(r, root, scene);

    const json empty = json::object();
    const json& b = root.value("blades", empty);
    r.onlyKeys(b, "blades",
               {"density_per_m2", "tuft_fraction", "tuft_blades", "tuft_radius_m", "tuft_spacing_m",
                "height_scale", "width_scale", "stiffness", "seed", "density_map"});
    BladeSeeding& s = scene.blades;
    s.density_per_m2 = r.number(b, "density_per_m2", "blades", s.density_per_m2, 0.f, 1e5f);
    s.tuftFraction = r.number(b, "tuft_fraction", "blades", s.tuftFraction, 0.f, 1.f);
    const glm::vec2 tuftBlades =
        r.range(b, "tuft_blades", "blades", {s.tuftBladesMin, s.tuftBladesMax}, 1.f, 1000.f);
    s.tuftBladesMin = static_cast<int>(tuftBlades.x);
    s.tuftBladesMax = static_cast<int>(tuftBlades.y);
    s.tuftRadius_m = r.number(b, "tuft_radius_m", "blades", s.tuftRadius_m, 0.f, 10.f);
    s.tuftSpacing_m = r.number(b, "tuft_spacing_m", "blades", s.tuftSpacing_m, 0.f, 100.f);
    s.heightScale = r.range(b, "height_scale", "blades", s.heightScale, 0.01f, 100.f);
    s.widthScale = r.range(b, "width_scale", "blades", s.widthScale, 0.01f, 100.f);
    s.stiffness = r.range(b, "stiffness", "blades", s.stiffness, 0.f, 100.f);
    s.seed = static_cast<std::uint32_t>(
        r.integer(b, "seed", "blades", static_cast<int>(s.seed), 0, 2147483647));
    if (b.contains("density_map")) {
        s.densityMap = readGroundImage(r, b.at("density_map"), "blades.density_map");
        // Read on load as well as when seeding, as archetypes.map is: a bad image fails before
        // any GL context exists, with the scene file and the field in the message.
        if (const std::string why = densityMapProblem(*s.densityMap); !why.empty())
            r.fail("blades.density_map.image", why);
    }

    const json& c = root.value("camera", empty);
    r.onlyKeys(c, "camera",
               {"position_m", "target_m", "path", "vertical_fov_deg", "near_m", "far_m"});
    CameraDescription& cam = scene.camera;
    cam.verticalFov_deg =
        r.number(c, "vertical_fov_deg", "camera", cam.verticalFov_deg, 1.f, 170.f);
    cam.near_m = r.number(c, "near_m", "camera", cam.near_m, 1e-4f, 1e4f);
    cam.far_m = r.number(c, "far_m", "camera", cam.far_m, 1e-3f, 1e6f);
    if (!(cam.far_m > cam.near_m)) r.fail("camera.far_m", "must be greater than near_m");
    if (c.contains("path")) {
        if (c.contains("position_m") || c.contains("target_m"))
            r.fail("camera", "give either position_m/target_m or path, not both");
        if (!c.at("path").is_array() || c.at("path").empty())
            r.fail("camera.path", "expected a non-empty array");
        for (std::size_t i = 0; i < c.at("path").size(); ++i) {
            const json& k = c.at("path")[i];
            const std::string where = "camera.path[" + std::to_string(i) + "]";
            r.onlyKeys(k, where, {"time_s", "position_m", "target_m"});
            CameraKey key{r.number(k, "time_s", where, 0.f, 0.f, 1e6f),
                          r.vec3(k, "position_m", where, {}), r.vec3(k, "target_m", where, {})};
            if (!cam.path.empty() && !(key.time_s > cam.path.back().time_s))
                r.fail(where + ".time_s", "keys must be in increasing time");
            cam.path.push_back(key);
        }
    } else {
        const CameraKey fallback;
        cam.path.push_back({0.f, r.vec3(c, "position_m", "camera", fallback.position_m),
                            r.vec3(c, "target_m", "camera", fallback.target_m)});
    }
    for (const CameraKey& k : cam.path)
        if (k.position_m == k.target_m) r.fail("camera", "position_m and target_m must differ");

    const json& l = root.value("light", empty);
    r.onlyKeys(l, "light", {"direction", "intensity", "ambient", "sky_color"});
    scene.light.direction =
        normalised(r, r.vec3(l, "direction", "light", scene.light.direction), "light.direction");
    scene.light.intensity = r.number(l, "intensity", "light", scene.light.intensity, 0.f, 100.f);
    scene.light.ambient = r.number(l, "ambient", "light", scene.light.ambient, 0.f, 10.f);
    scene.light.skyColor = r.vec3(l, "sky_color", "light", scene.light.skyColor);

    const json& w = root.value("wind", empty);
    // The field was named as an acceleration but always fed the wave amplitude (m/s).
    if (w.contains("strength_m_s2"))
        r.fail("wind.strength_m_s2",
               "renamed to wave_amplitude_m_s (the wind pushes the tip with a velocity, m/s); "
               "rename the field, its value keeps its meaning");
    r.onlyKeys(w, "wind",
               {"direction", "wave_amplitude_m_s", "wavelength_m", "frequency_hz", "source_m",
                "source_amplitude_m_s", "source_radius_m"});
    WindDescription& wind = scene.wind;
    wind.direction =
        normalised(r, r.vec3(w, "direction", "wind", wind.direction), "wind.direction");
    wind.waveAmplitude_m_s =
        r.number(w, "wave_amplitude_m_s", "wind", wind.waveAmplitude_m_s, 0.f, 1000.f);
    wind.wavelength_m = r.number(w, "wavelength_m", "wind", wind.wavelength_m, 1e-3f, 1e6f);
    wind.frequency_hz = r.number(w, "frequency_hz", "wind", wind.frequency_hz, 0.f, 100.f);
    wind.source_m = r.vec3(w, "source_m", "wind", wind.source_m);
    wind.sourceAmplitude_m_s =
        r.number(w, "source_amplitude_m_s", "wind", wind.sourceAmplitude_m_s, 0.f, 1000.f);
    wind.sourceRadius_m = r.number(w, "source_radius_m", "wind", wind.sourceRadius_m, 1e-3f, 1e6f);

    if (root.contains("colliders")) {
        if (!root.at("colliders").is_array()) r.fail("colliders", "expected an array of spheres");
        for (std::size_t i = 0; i < root.at("colliders").size(); ++i) {
            const json& k = root.at("colliders")[i];
            const std::string where = "colliders[" + std::to_string(i) + "]";
            r.onlyKeys(k, where, {"center_m", "radius_m", "velocity_m_s"});
            scene.colliders.push_back({r.vec3(k, "center_m", where, {}),
                                       r.number(k, "radius_m", where, 0.2f, 1e-4f, 1e4f),
                                       r.vec3(k, "velocity_m_s", where, {})});
        }
    }

    const json& p = root.value("physics", empty);
    r.onlyKeys(p, "physics",
               {"enabled", "gravity_direction", "gravity_m_s2", "gravity_center_m",
                "gravity_center_m_s2", "gravity_center_mix", "collision_decay_per_s"});
    PhysicsDescription& ph = scene.physics;
    ph.enabled = r.boolean(p, "enabled", "physics", ph.enabled);
    ph.gravityDirection =
        normalised(r, r.vec3(p, "gravity_direction", "physics", ph.gravityDirection),
                   "physics.gravity_direction");
    ph.gravity_m_s2 = r.number(p, "gravity_m_s2", "physics", ph.gravity_m_s2, 0.f, 1000.f);
    ph.gravityCenter_m = r.vec3(p, "gravity_center_m", "physics", ph.gravityCenter_m);
    ph.gravityCenter_m_s2 =
        r.number(p, "gravity_center_m_s2", "physics", ph.gravityCenter_m_s2, 0.f, 1000.f);
    ph.gravityCenterMix =
        r.number(p, "gravity_center_mix", "physics", ph.gravityCenterMix, 0.f, 1.f);
    ph.collisionDecay_per_s =
        r.number(p, "collision_decay_per_s", "physics", ph.collisionDecay_per_s, 0.f, 1000.f);

    const json& k = root.value("culling", empty);
    r.onlyKeys(k, "culling",
               {"orientation", "frustum", "distance", "occlusion", "orientation_threshold",
                "max_distance_m", "distance_levels"});
    CullingDescription& cull = scene.culling;
    cull.orientation = r.boolean(k, "orientation", "culling", cull.orientation);
    cull.frustum = r.boolean(k, "frustum", "culling", cull.frustum);
    cull.distance = r.boolean(k, "distance", "culling", cull.distance);
    cull.occlusion = r.boolean(k, "occlusion", "culling", cull.occlusion);
    cull.orientationThreshold =
        r.number(k, "orientation_threshold", "culling", cull.orientationThreshold, 0.f, 1.f);
    cull.maxDistance_m = r.number(k, "max_distance_m", "culling", cull.maxDistance_m, 0.f, 1e6f);
    cull.distanceLevels = r.integer(k, "distance_levels", "culling", cull.distanceLevels, 1, 1000);

    const json& v = root.value("render", empty);
    r.onlyKeys(v, "render",
               {"size_px", "msaa_samples", "frame_rate_hz", "patch_size", "shape", "displacement",
                "max_tess_level", "min_width_px", "root_color", "tip_color", "translucency",
                "ao_at_root"});
    RenderSettings& rs = scene.render;
    if (v.contains("size_px")) {
        const json& size = v.at("size_px");
        if (!size.is_array() || size.size() != 2 || !size[0].is_number_integer() ||
            !size[1].is_number_integer() || size[0].get<int>() < 1 || size[1].get<int>() < 1 ||
            size[0].get<int>() > kMaxImageSide_px || size[1].get<int>() > kMaxImageSide_px)
            r.fail("render.size_px", "expected [width, height] in pixels, each 1.." +
                                         std::to_string(kMaxImageSide_px));
        rs.width_px = size[0].get<int>();
        rs.height_px = size[1].get<int>();
    }
    rs.msaaSamples = r.integer(v, "msaa_samples", "render", rs.msaaSamples, 1, 16);
    rs.frameRate_hz = r.number(v, "frame_rate_hz", "render", rs.frameRate_hz, 1e-3f, 1e4f);
    rs.patchSize = r.integer(v, "patch_size", "render", rs.patchSize, 1, 1 << 20);
    if (v.contains("shape")) {
        const std::string shape = v.at("shape").is_string() ? v.at("shape").get<std::string>() : "";
        const char* names[] = {"quad", "triangle", "quadratic", "triangle-tip"};
        rs.shapeOverride = -2;
        if (shape == "archetype") rs.shapeOverride = -1;
        for (int i = 0; i < 4; ++i)
            if (shape == names[i]) rs.shapeOverride = i;
        if (rs.shapeOverride == -2)
            r.fail("render.shape",
                   "expected \"archetype\", \"quad\", \"triangle\", \"quadratic\" or "
                   "\"triangle-tip\"");
    }
    rs.displacement = r.boolean(v, "displacement", "render", rs.displacement);
    rs.maxTessLevel = r.number(v, "max_tess_level", "render", rs.maxTessLevel, 1.f, 64.f);
    rs.minWidth_px = r.number(v, "min_width_px", "render", rs.minWidth_px, 0.f, 100.f);
    rs.rootColor = r.vec3(v, "root_color", "render", rs.rootColor);
    rs.tipColor = r.vec3(v, "tip_color", "render", rs.tipColor);
    rs.translucency = r.number(v, "translucency", "render", rs.translucency, 0.f, 1.f);
    rs.aoAtRoot = r.number(v, "ao_at_root", "render", rs.aoAtRoot, 0.f, 1.f);
    return scene;
}

SceneDescription loadSceneDescription(const fs::path& sceneFile) {
    std::ifstream in(sceneFile, std::ios::binary);
    if (!in)
        throw RuntimeError("cannot read scene file " + sceneFile.string() + "; check the path");
    std::stringstream text;
    text << in.rdbuf();
    return parseSceneDescription(text.str(), sceneFile);
}

}  // namespace meadow::runtime
