#pragma once
// Synthetic tufts with ground truth: blades of known archetype fanning from a common base, seen
// from the side by a depth camera, in front of a ground plane and a back wall. The simulated
// sensor (capture/simulated_sensor.h) renders them; the truth (spines, widths, labels) is exact.
//
// World space follows glTF (metres, right-handed, +Y up). The tuft stands on the ground plane
// y = 0 around the origin; the camera looks along -Z at the tuft from +Z, so world +X is image
// right. A blade's frame is its archetype's blade-local frame (archetype.h) placed by
// worldFromBlade = translate(base) * rotateZ(-lean) * rotateY(yaw) * [rotateY(pi) if it bends
// toward -X]: its face plane faces the camera (front or back face), it leans by `lean` from
// vertical and bends in its face plane toward the side it was given.
#include <cstdint>
#include <functional>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "meadow/capture/intrinsics.h"
#include "meadow/modeling/archetype.h"
#include "meadow/modeling/blade_mesh.h"
#include "meadow/synth/labelled_mesh.h"

namespace meadow::synth {

using modeling::AnalyticShape;
using modeling::Archetype;
using modeling::BladeMeshOptions;
using modeling::QuadraticBezier;
using modeling::TriangleMesh;

// How one blade stands in a tuft. Angles in radians.
struct BladePlacement {
    Archetype archetype;  // at rest, blade-local frame, bending toward +X
    BladeMeshOptions mesh;
    glm::vec3 base_m{0.f};         // world position of v0 (on the ground, y = 0)
    float lean_rad = 0.f;          // from vertical, positive toward world +X (image right)
    float yaw_rad = 0.f;           // about the blade's up axis: turns the face off square-on
    bool bendsTowardPlusX = true;  // world side (image side) the blade bends toward
    // Out of the face plane: the tip turns by this angle toward the camera about the base, the
    // base direction is kept and v1 re-solved so the length stays (a blade curling forward).
    float curlTowardCamera_rad = 0.f;
    float gustPhase_rad = 0.f;  // this blade's phase in the wind's gust function
};

// The camera looks at `target_m` (world) from `distance_m` away, pitched down by `tilt_rad`
// (0 = horizontal side view).
struct TuftCamera {
    capture::Intrinsics intrinsics = capture::Intrinsics::kinectV1();
    glm::vec3 target_m{0.f, 0.12f, 0.f};
    float distance_m = 0.8f;
    float tilt_rad = 0.f;
    [[nodiscard]] glm::mat4 cameraFromWorld() const;
};

// Gusting wind along world +X. Each blade's tip is displaced by
//   d(t) = tipDisplacementPerHeight * height * gust(t)
// and v1 re-solved so the spine keeps its length (spineWithLength below).
struct TuftWind {
    float tipDisplacementPerHeight = 0.f;  // 0 = no wind; 0.35 is a strong gust
    float gustFrequency_hz = 1.2f;
    float frameRate_hz = 30.f;
    // Smooth gust strength in [0, 1] at time t_s for a blade with phase phase_rad: a raised
    // cosine gust modulated by a faster, weaker turbulence term.
    [[nodiscard]] float gust(double t_s, float phase_rad) const;
};

struct TuftSpec {
    std::vector<BladePlacement> blades;
    TuftCamera camera;
    TuftWind wind;
    bool scenery = true;        // ground plane and back wall (label 0)
    float wallBehind_m = 0.4f;  // back wall distance behind the tuft's base
};

// One blade of one frame with everything its truth needs.
struct SyntheticBlade {
    std::uint16_t id = 0;  // its label in the label image, 1..; 0 is "not a blade"
    Archetype archetype;   // this frame's spine (wind, curl applied), blade-local
    BladeMeshOptions mesh;
    glm::mat4 cameraFromBlade{1.f};  // rigid

    [[nodiscard]] QuadraticBezier spineInCamera_m() const;
    [[nodiscard]] TriangleMesh meshInCamera() const;
};

// One frame: blades and scenery in camera space.
struct SyntheticTuft {
    std::vector<SyntheticBlade> blades;
    std::vector<synth::LabelledMesh> scenery;  // label 0
    glm::mat4 cameraFromWorld{1.f};
    double timestamp_s = 0.0;

    // Everything for SimulatedSensor::render: scenery, then the blades labelled by id.
    [[nodiscard]] std::vector<synth::LabelledMesh> meshes() const;
};

// Frame `frame` of the tuft: blade i gets id i + 1. Throws std::invalid_argument on an empty
// or over-long (> 65535) blade list or a negative frame.
[[nodiscard]] SyntheticTuft buildTuft(const TuftSpec& spec, int frame);

// The spine from v0 to v2 with arc length length_m whose v1 lies on the ray from v0 along
// baseDirection (so the blade keeps its base tangent), found by bisection on |v1 - v0|.
// Requires |v2 - v0| < length_m (std::invalid_argument otherwise).
[[nodiscard]] QuadraticBezier spineWithLength(const glm::vec3& v0, const glm::vec3& baseDirection,
                                              const glm::vec3& v2, float length_m);

// What a preset is built from; zero/negative fields mean "the preset's default".
struct TuftParams {
    std::uint64_t seed = 1;
    float distance_m = 0.f;
    int bladeCount = 0;
    capture::Intrinsics intrinsics = capture::Intrinsics::kinectV1();
};

struct SynthPreset {
    std::string name;
    std::string description;      // one line
    float distance_m = 0.8f;      // default camera distance
    int bladeCount = 5;           // default number of blades
    float noiseMultiplier = 1.f;  // applied on top of the user's noise scale ("noisy": 3)
    // The tuft (deterministic in params.seed); params carry resolved distance and count.
    std::function<TuftSpec(const TuftParams& params)> build;
};

// The catalog, in the order `meadow synth --list` shows it.
[[nodiscard]] const std::vector<SynthPreset>& synthPresets();
// nullptr when no preset has that name.
[[nodiscard]] const SynthPreset* findSynthPreset(std::string_view name);
// "slim-grass, quadratic-leaf, ..." for messages.
[[nodiscard]] std::string synthPresetNames();
// The preset's spec with params' zero fields filled from the preset's defaults.
[[nodiscard]] TuftSpec buildPresetSpec(const SynthPreset& preset, TuftParams params);

// Limits the presets are designed for: the tuft fits the image and the sensor's range.
inline constexpr float kMinSynthDistance_m = 0.5f;
inline constexpr float kMaxSynthDistance_m = 1.2f;
inline constexpr int kMinSynthBlades = 1;
inline constexpr int kMaxSynthBlades = 12;

}  // namespace meadow::synth
