#pragma once
// A scanned plant (scanned_plant.h) as a depth camera sees it on a phenotyping bench: in a pot on
// a floor before a wall, with clutter behind it, the camera at a distance looking down at a
// pitch, the plant turned on a turntable between views (the camera, pot and room stay). Each
// view is rendered through the simulated sensor with the truth of every organ in it.
//
// World: +Y up, the stem's foot at the origin on the pot's soil, the camera on +Z at azimuth 0.
// Label images: organ ids 1..N (PlantTruthOrgan::id, in the plant's label order), and the
// scenery's labels below; 0 is nothing within the sensor's range.
#include <cstdint>
#include <functional>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "meadow/capture/intrinsics.h"
#include "meadow/synth/labelled_mesh.h"
#include "meadow/synth/scanned_plant.h"
#include "meadow/synth/simulated_sensor.h"

namespace meadow::synth {

inline constexpr std::uint16_t kFloorLabel = 65001;
inline constexpr std::uint16_t kWallLabel = 65002;
inline constexpr std::uint16_t kPotLabel = 65003;  // the pot and its soil
inline constexpr std::uint16_t kClutterLabel = 65004;

struct PlantViewOptions {
    float distance_m =
        0.f;  // camera centre to the aim point; 0: the plant fills 70 % of the height
    float pitch_deg = 20.f;     // the camera looks down by this
    float azimuth_deg = 0.f;    // the plant turned about its stem in the first view
    int views = 1;              // turntable: views 360 / views degrees apart
    float aimHeight_m = -1.f;   // aim point above the foot; < 0: half the plant's height
    bool scenery = true;        // pot, floor, wall and clutter
    float wallBehind_m = 0.6f;  // the wall's distance behind the stem
    std::uint64_t seed = 1;     // where the clutter stands
};

struct PlantTruthOrgan {
    int id = 0;           // its value in the label images
    int sourceLabel = 0;  // its id in the scanned plant's file
    bool stem = false;
    std::vector<glm::vec3> centreLineCamera_m;  // a leaf: from where it leaves the stem to its tip
    float length_m = 0.f;                       // along the centre line
    float maxWidth_m = 0.f;                     // a leaf's widest; the stem's diameter
    int visiblePixels = 0;                      // pixels labelled with it in this view
    float visibleShare = 0.f;  // share of its scanned points the camera sees in this view
};

struct PlantTruthView {
    int index = 0;
    float azimuth_deg = 0.f;
    std::string labels;  // label image, relative to the truth folder ("labels/000000.png")
    glm::mat4 cameraFromWorld{1.f};  // world as above, the plant turned by azimuth_deg
    std::vector<PlantTruthOrgan> organs;
};

struct PlantTruth {
    std::string plant;   // the scanned plant's name
    std::string source;  // its file
    std::string unit;    // the unit it was read in
    std::string stemFoundBy;
    std::string sensor;  // the simulated sensor, one line
    float noiseScale = 1.f;
    capture::Intrinsics intrinsics;
    PlantViewOptions options;
    std::vector<PlantTruthView> views;
};

struct RenderedPlantView {
    SimulatedFrame frame;
    PlantTruthView truth;
};

// `options` with the distance and aim height it leaves to the plant (0, < 0) worked out: where
// the plant fills 70 % of the image's height (no nearer than 0.8 m), aimed at its middle.
[[nodiscard]] PlantViewOptions resolvedPlantViewOptions(const ScannedPlant& plant,
                                                        const PlantViewOptions& options,
                                                        const capture::Intrinsics& intrinsics);

// Renders every view. `progress(done, total)` after each. Throws SynthError for options out of
// range (distance 0 or 0.2-10 m, pitch -30-89 deg, 1-360 views).
[[nodiscard]] std::vector<RenderedPlantView> renderPlantViews(
    const ScannedPlant& plant, const PlantViewOptions& options, const SimulatedSensor& sensor,
    std::uint64_t seed, const std::function<void(int done, int total)>& progress = {});

}  // namespace meadow::synth
