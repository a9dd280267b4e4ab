#pragma once
// What stands around a plant on a phenotyping bench (plant_views.h): a pot with its soil, the
// floor the pot stands on, a wall behind, and clutter (boxes) between the plant and the wall.
// World: +Y up, the stem's foot at the origin, the camera on +Z.
#include <cstdint>
#include <vector>

#include "meadow/synth/labelled_mesh.h"

namespace meadow::synth::plant {

struct Scenery {
    float potRadius_m = 0.f, potHeight_m = 0.f;
    std::vector<LabelledMesh> meshes;  // world coordinates
};

// Pot sized to the plant (a tenth of its height in radius, 4-15 cm), floor under the pot, the
// wall wallBehind_m behind the stem, one or two boxes of clutter placed by `seed`.
Scenery benchScenery(float plantHeight_m, float wallBehind_m, std::uint64_t seed);

}  // namespace meadow::synth::plant
