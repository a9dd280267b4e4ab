#pragma once
// `meadow synth`: renders a synthetic tuft preset through the simulated sensor into a recording
// folder (capture/recording.h) with exact ground truth beside it:
//
//   OUT/recording.json, OUT/depth/000000.png ...   the recording (16-bit mm, 0 = no reading)
//   OUT/truth/blades.json                          "meadow.synth-truth" version 1 (below)
//   OUT/truth/labels/000000.png ...                16-bit blade id per pixel, 0 = no blade
//
// Every file is written atomically. The same options give the same files, byte for byte.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/mat4x4.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "meadow/capture/intrinsics.h"
#include "meadow/modeling/quadratic_bezier.h"
#include "meadow/synth/synthetic_tuft.h"

namespace meadow::synth {

using modeling::QuadraticBezier;

inline constexpr std::string_view kSynthTruthFormatName = "meadow.synth-truth";
inline constexpr int kSynthTruthFormatVersion = 1;

// One blade of one frame, as blades.json records it. Camera space: OpenCV's pinhole convention
// (x right, y down, z forward), metres.
struct SynthTruthBlade {
    int id = 0;                        // label image value, 1..
    std::string archetype;             // blade type name ("slim-grass", ...)
    float height_m = 0.f;              // arc length of the spine
    QuadraticBezier spineCamera_m;     // v0 (base), v1, v2 (tip) in camera space
    std::vector<float> widthFraction;  // arc-length fractions s of the width samples, 0..1
    std::vector<float> width_m;        // full width at each s, in the face plane, across the spine
    float leftWidthFraction = 0.5f;    // share of the width on the blade's left (-X local) side
    float twistAtTip_rad = 0.f;        // ribbon twist about the spine at the tip (blade_mesh.h)
    glm::vec3 faceNormalCamera{0.f, 0.f, -1.f};  // unit face normal at the base, camera space
};

struct SynthTruthFrame {
    int index = 0;
    double timestamp_s = 0.0;
    std::string labels;  // label image, relative to the truth folder ("labels/000000.png")
    std::vector<SynthTruthBlade> blades;
};

struct SynthTruth {
    std::string preset;
    std::uint64_t seed = 0;
    float noiseScale = 1.f;  // as given; the sensor ran at noiseScale x the preset's multiplier
    float sensorNoiseScale = 1.f;
    float distance_m = 0.f;  // camera centre to the tuft's aim point
    float cameraTilt_rad = 0.f;
    capture::Intrinsics intrinsics;
    glm::mat4 cameraFromWorld{1.f};  // world: glTF, +Y up, the tuft's base near the origin
    std::vector<SynthTruthFrame> frames;
};

bool operator==(const SynthTruthBlade&, const SynthTruthBlade&);
bool operator==(const SynthTruthFrame&, const SynthTruthFrame&);
bool operator==(const SynthTruth&, const SynthTruth&);

// The truth of one built frame.
[[nodiscard]] SynthTruthFrame truthOfFrame(const SyntheticTuft& tuft, int frameIndex);

// JSON text of blades.json, and back. Reading throws SynthError naming `sourceName`, the
// offending field and what to do on malformed JSON, an unknown format or version, or a bad
// value.
[[nodiscard]] std::string synthTruthToJson(const SynthTruth& truth);
[[nodiscard]] SynthTruth parseSynthTruth(std::string_view json, const std::string& sourceName);
[[nodiscard]] SynthTruth readSynthTruth(const std::filesystem::path& file);

struct SynthOptions {
    std::string preset;
    std::filesystem::path out;  // recording folder; created, or replaced if it is one
    int frames = 3;
    std::uint64_t seed = 1;
    float noiseScale = 1.f;  // multiplies every random term of the sensor's noise (0 = none)
    float distance_m = 0.f;  // 0: the preset's default
    int bladeCount = 0;      // 0: the preset's default
};

inline constexpr int kMaxSynthFrames = 10000;

// The rate `meadow synth` stamps its frames at, as if the sensor ran at its native rate (Kinect
// v1: 30 Hz); the wind presets move by it. Whoever renders a preset in memory uses it too.
inline constexpr double kSynthFrameRate_hz = 30.0;

// The simulated sensor's noise seed for frame `frame` of a synth run seeded `seed`: SplitMix64
// (Steele, Lea & Flood 2014), so neighbouring seeds and frames share no noise. Whoever renders a
// preset in memory uses it to get the frames `meadow synth` writes.
[[nodiscard]] std::uint64_t synthFrameSeed(std::uint64_t seed, std::uint64_t frame);

// Renders and writes everything; returns the truth it wrote. `progress(done, total)` is called
// after each frame. Throws SynthError on an unknown preset (naming the known ones) and
// capture::CaptureError / meadow::Error when the disk refuses; std::invalid_argument on
// options out of range (frames in [1, kMaxSynthFrames], noise in [0, 100], distance and blade
// count within synthetic_tuft.h's limits).
SynthTruth synthesize(const SynthOptions& options,
                      const std::function<void(int done, int total)>& progress = {});

}  // namespace meadow::synth
