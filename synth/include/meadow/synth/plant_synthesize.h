#pragma once
// `meadow synth --plant`: a scanned plant (scanned_plant.h) rendered on a phenotyping bench
// (plant_views.h) through a simulated sensor into a recording folder, with its truth:
//
//   OUT/recording.json, OUT/depth/000000.png ...   one frame per turntable view
//   OUT/truth/plant.json                           "meadow.plant-truth" version 1 (below)
//   OUT/truth/labels/000000.png ...                16-bit organ id per pixel (plant_views.h)
//
// Every file is written atomically; the same options give the same files, byte for byte.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "meadow/synth/plant_views.h"
#include "meadow/synth/scanned_plant.h"

namespace meadow::synth {

inline constexpr std::string_view kPlantTruthFormatName = "meadow.plant-truth";
inline constexpr int kPlantTruthFormatVersion = 1;

[[nodiscard]] std::string plantTruthToJson(const PlantTruth& truth);
// Throws SynthError naming `sourceName`, the field and what to do.
[[nodiscard]] PlantTruth parsePlantTruth(std::string_view json, const std::string& sourceName);
[[nodiscard]] PlantTruth readPlantTruth(const std::filesystem::path& file);

struct PlantSynthOptions {
    std::filesystem::path plant;
    ScannedPlantOptions scan;
    PlantViewOptions views;
    std::string sensor = "kinect-v1";  // a simulated sensor model's name
    float noiseScale = 1.f;            // multiplies every random term of its noise (0 = none)
    std::uint64_t seed = 1;            // sensor noise
    std::filesystem::path out;         // recording folder; created, or replaced if it is one
};

// The simulated sensors a plant can be rendered through, by name.
[[nodiscard]] std::vector<std::string> plantSensorNames();

// Renders and writes everything; returns the truth written. Throws SynthError on a plant that
// cannot be read, an unknown sensor, or options out of range, and meadow::Error when the disk
// refuses.
PlantTruth synthesizePlant(const PlantSynthOptions& options,
                           const std::function<void(int done, int total)>& progress = {});

}  // namespace meadow::synth
