#pragma once
// A scene file (JSON, format "meadow.scene", version 1; docs/formats.md#scene): the meshes grass
// grows on, opaque props, the archetypes, how blades are seeded, camera, light, wind, colliders,
// physics, culling and render settings. loadSceneDescription() reads and checks it; the renderer
// turns it into GPU buffers.
#include <cstdint>
#include <filesystem>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "meadow/modeling/archetype.h"
#include "meadow/runtime/physics.h"

namespace meadow::runtime {

inline constexpr std::string_view kSceneFormat = "meadow.scene";
inline constexpr int kSceneVersion = 1;

struct SceneMesh {
    std::filesystem::path gltf;            // .glb or .gltf, resolved against the scene's folder
    glm::vec3 albedo{0.25f, 0.2f, 0.12f};  // linear colour of the opaque surface
};

// An image laid over the world's XZ plane, looked up at a blade's root (nearest texel, clamped
// at the border; runtime/src/ground_maps.h).
struct GroundImage {
    std::filesystem::path image;
    glm::vec2 minXZ_m{0.f};  // world XZ of the image's first column / row
    glm::vec2 maxXZ_m{1.f};  // world XZ of its last column / row
};
// 8/16-bit grey image; white keeps every blade, black none.
using DensityMap = GroundImage;
// 8-bit grey image; value k plants archetype k (in the library's order), 255 picks by weight.
using ArchetypeMap = GroundImage;

struct BladeSeeding {
    float density_per_m2 = 300.f;  // blades per square metre of surface (before the density map)
    float tuftFraction = 0.5f;     // fraction of the blades that grow in tufts, the rest single
    int tuftBladesMin = 5;         // blades per tuft, uniform in [min, max]
    int tuftBladesMax = 12;
    float tuftRadius_m = 0.04f;         // blades of a tuft grow within this distance of its centre
    float tuftSpacing_m = 0.0f;         // Poisson-disk distance between tuft centres; 0 = derived
    glm::vec2 heightScale{0.8f, 1.2f};  // uniform range, times the archetype's height
    glm::vec2 widthScale{0.8f, 1.2f};   // uniform range, times the archetype's width
    // Uniform range of the physics stiffness s (1/s): how fast a bent blade springs back (it
    // halves its bend in ln 2 / s seconds) and how little gravity and wind bend it (by their
    // push over s). Grass that stands and sways: 10-20.
    glm::vec2 stiffness{12.f, 18.f};
    std::uint32_t seed = 1;  // the same seed gives the same meadow
    std::optional<DensityMap> densityMap;
};

struct CameraKey {
    float time_s = 0.f;
    glm::vec3 position_m{0.f, 1.5f, 4.f};
    glm::vec3 target_m{0.f};
};

struct CameraDescription {
    std::vector<CameraKey> path;  // one key: a still camera; more: linear in time
    float verticalFov_deg = 50.f;
    float near_m = 0.05f;
    float far_m = 200.f;
};

struct LightDescription {
    glm::vec3 direction{0.4f, 0.8f, 0.3f};  // toward the light (world), normalised on load
    float intensity = 1.1f;
    float ambient = 0.25f;
    glm::vec3 skyColor{0.55f, 0.7f, 0.9f};  // display colour of the background (at the horizon)
    // Display colour straight up; the sky blends from skyColor at the horizon to it. Unset: the
    // sky is one colour.
    std::optional<glm::vec3> zenithColor;
    // Aerial perspective: a surface this far away keeps 1/e of its colour and takes the rest from
    // the horizon's sky colour. 0: no fog.
    float fogDistance_m = 0.f;
};

// Shadows of blades and props from the light (a shadow map centred on the near field).
struct ShadowDescription {
    bool enabled = false;
    int mapSize_px = 2048;
    float distance_m = 30.f;  // the map covers this far from the camera
    float strength = 0.6f;    // the share of direct light a shadow takes away
};

// A height field the grass grows on, for scenes too large for a mesh of blades: value-noise
// relief over a rectangle of the world's XZ plane (runtime/src/terrain.h).
struct TerrainDescription {
    glm::vec2 minXZ_m{-500.f};
    glm::vec2 maxXZ_m{500.f};
    int samples = 257;            // grid points along each side
    float relief_m = 12.f;        // the heights span about this much
    float featureSize_m = 180.f;  // the size of the largest hills
    std::uint32_t seed = 1;
    glm::vec3 albedo{0.16f, 0.12f, 0.06f};  // the soil
    // The y of camera keys, camera targets and collider positions counts from the terrain
    // under them, so a path can be written without knowing the hills.
    bool relativeHeights = true;
};

// Tile instancing (Fan & Sheng, Sec. 4.5): the terrain is cut into square tiles that all draw the
// same patch of blades, seeded once with the scene's `blades` settings, turned per tile and
// thinned by the density map and with distance. Blades are simulated only in tiles near the
// camera or a collider; the others stand in their rest pose swayed by the wind. Beyond the near
// distance the grass is drawn as slices on the terrain (the far field).
struct TilingDescription {
    float tileSize_m = 4.f;
    float nearDistance_m = 40.f;        // blades are geometry up to here
    float transition_m = 10.f;          // blades fade out and the far field in over this band
    float fullDensityDistance_m = 8.f;  // beyond, the blades thin as (this / distance)^2
    float activeDistance_m = 6.f;       // tiles this close to the camera or a collider simulate
    int poolTiles = 96;                 // tiles simulated at once at most
    int maxDrawnBlades = 1 << 20;       // blades drawn in one frame at most
    bool farField = true;
};

// Wind of Jahrmann & Wimmer 2017, Sec. 5.1. It pushes the tip with a velocity (v2 += w dt), so
// its amplitudes are in m/s. The wave and the source's rings share wavelength and frequency.
struct WindDescription {
    glm::vec3 direction{1.f, 0.f, 0.f};  // world, normalised on load
    float waveAmplitude_m_s = 2.f;       // travelling wave along direction, in [0, A]
    float wavelength_m = PhysicsSettings{}.windWavelength_m;
    float frequency_hz = 0.4f;  // gust frequency: the waves' period is 1 / frequency
    glm::vec3 source_m = PhysicsSettings{}.windSource_m;  // point source (a fan, a helicopter)
    float sourceAmplitude_m_s = PhysicsSettings{}.windSource_mps;  // 0: no point source
    float sourceRadius_m = PhysicsSettings{}.windSourceRadius_m;   // fades linearly to 0 here
    // Gusts and turbulence carried across the meadow (PhysicsSettings: Habel et al. 2007).
    float gustAmplitude_m_s = PhysicsSettings{}.windGust_mps;
    float gustSize_m = PhysicsSettings{}.windGustSize_m;
    float gustSpeed_m_s = PhysicsSettings{}.windGustSpeed_mps;
    float turbulenceAmplitude_m_s = PhysicsSettings{}.windTurbulence_mps;
    float turbulenceSize_m = PhysicsSettings{}.windTurbulenceSize_m;
};

// Where a moving collider is at a time (a camera path's keys without a target).
struct ColliderKey {
    float time_s = 0.f;
    glm::vec3 position_m{0.f};
};

// Something that presses blades: a sphere, or a closed glTF mesh approximated by spheres
// (runtime/src/sphere_packing.h). It moves linearly with a velocity or along a path of keys, and
// is drawn as an opaque mesh unless hidden.
struct ColliderDescription {
    glm::vec3 center_m{0.f};  // the sphere's centre, or where the mesh's origin is placed
    float radius_m = 0.2f;    // sphere only
    glm::vec3 velocity_m_s{0.f};
    std::vector<ColliderKey> path;              // instead of center_m + velocity: linear between
    std::optional<std::filesystem::path> gltf;  // a mesh collider, resolved against the scene
    int maxSpheres = 32;                        // a mesh collider's sphere budget
    bool visible = true;
    glm::vec3 albedo{0.42f, 0.36f, 0.3f};

    // Where center_m has moved to at time_s: along the path (held before its first and after its
    // last key), or center_m + velocity_m_s * time_s.
    [[nodiscard]] glm::vec3 positionAt(float time_s) const;
};

// Environmental gravity, Eq. (3): direction D and centre C, blended by gravityCenterMix (t).
struct PhysicsDescription {
    bool enabled = true;
    glm::vec3 gravityDirection = PhysicsSettings{}.gravityDirection;  // normalised on load
    float gravity_m_s2 = PhysicsSettings{}.gravity_mps2;
    glm::vec3 gravityCenter_m = PhysicsSettings{}.gravityCenter_m;  // a planet's centre
    float gravityCenter_m_s2 = PhysicsSettings{}.gravityCenter_mps2;
    float gravityCenterMix = PhysicsSettings{}.gravityCenterMix;    // t: 0 direction, 1 centre
    float collisionDecay_per_s = PhysicsSettings{}.etaDecay_per_s;  // how fast eta fades
};

struct CullingDescription {
    bool orientation = true;
    bool frustum = true;
    bool distance = true;
    bool occlusion = true;
    // |dot(view, width direction)| above this is culled. 0.97 (not the paper's 0.9): only blades
    // within 14 deg of edge-on, which show under a quarter of their width; 0.9 visibly thins the
    // meadow (see docs/rendering.md#culling).
    float orientationThreshold = 0.97f;
    // Eq. (15) thins from d_max / n on: 100 m / 4 levels = 25 m, where a 1 cm blade is under
    // half a pixel even at 1080p; thinning nearer than that shows.
    float maxDistance_m = 100.f;
    int distanceLevels = 4;
};

struct RenderSettings {
    int width_px = 640;
    int height_px = 360;
    int msaaSamples = 4;
    float frameRate_hz = 30.f;  // simulated time step between frames is 1 / frameRate_hz
    int patchSize = 256;        // blades per patch, a multiple of BLADE_WORKGROUP_SIZE
    int shapeOverride = -1;     // -1: archetype's own; else modeling::AnalyticShape for all
    bool displacement = false;  // 3D displacement of the blade surface
    float maxTessLevel = 12.f;
    float minWidth_px = 1.f;                   // width correction
    glm::vec3 rootColor{0.05f, 0.16f, 0.02f};  // linear
    glm::vec3 tipColor{0.3f, 0.5f, 0.08f};     // linear
    float translucency = 0.5f;
    float aoAtRoot = 0.35f;
};

struct SceneDescription {
    std::filesystem::path file;          // the scene file itself
    std::vector<SceneMesh> grassMeshes;  // empty when the grass grows on a tiled terrain
    std::vector<SceneMesh> props;
    std::optional<TerrainDescription> terrain;
    std::optional<TilingDescription> tiling;  // set together with terrain
    std::vector<modeling::Archetype> archetypes;
    std::vector<float> archetypeWeights;       // one per archetype, > 0
    std::optional<ArchetypeMap> archetypeMap;  // checked on load (ground_maps.h)
    BladeSeeding blades;
    CameraDescription camera;
    LightDescription light;
    WindDescription wind;
    std::vector<ColliderDescription> colliders;
    PhysicsDescription physics;
    CullingDescription culling;
    ShadowDescription shadows;
    RenderSettings render;
};

// Reads, validates and resolves a scene file (loads the archetype library it names). Throws
// RuntimeError naming the file and the first problem.
SceneDescription loadSceneDescription(const std::filesystem::path& sceneFile);
// The same from JSON text; relative paths resolve against `baseDirectory`.
SceneDescription parseSceneDescription(const std::string& jsonText,
                                       const std::filesystem::path& origin);

}  // namespace meadow::runtime
