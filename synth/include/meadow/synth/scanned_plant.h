#pragma once
// A real scanned plant as test input: points with an organ label each (the stem or a leaf), in
// metres, in a world frame with +Y up and the stem's foot at the origin, and the truth of every
// organ: which is the stem, each leaf's centre line from where it leaves the stem to its tip, its
// length along that line and its widest width.
//
// Read from text, one point a line "x y z label" (Label3DMaize), or from PLY, ascii or binary
// (through PCL; a "label" property when present), with an optional skeleton graph, lines
// "v x y z organ" and "e i j" (Pheno4D), whose organ 0 is the stem and whose nearest edge labels
// each point. docs/formats.md, "Scanned plants".
#include <cstddef>
#include <filesystem>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "meadow/core/enum_names.h"

namespace meadow::synth {

enum class LengthUnit { Millimetre, Centimetre, Metre };
inline constexpr EnumNames<LengthUnit, 3> kLengthUnitNames{{{
    {LengthUnit::Millimetre, "mm"},
    {LengthUnit::Centimetre, "cm"},
    {LengthUnit::Metre, "m"},
}}};
[[nodiscard]] float metresPer(LengthUnit unit);

struct PlantOrgan {
    int label = 0;  // the file's organ id
    bool stem = false;
    // World, metres. A leaf: from its point nearest the stem (where it leaves it) to its tip
    // along the leaf; the stem: from its foot to its top.
    std::vector<glm::vec3> centreLine_m;
    float length_m = 0.f;    // along centreLine_m
    float maxWidth_m = 0.f;  // a leaf's widest cross-section; the stem's diameter
    std::size_t points = 0;
};

struct ScannedPlant {
    std::string name;                 // the file's stem ("v-9-1-l-r")
    std::vector<glm::vec3> points_m;  // world: +Y up, the stem's foot at the origin
    std::vector<int> labels;          // organ label of each point
    std::vector<PlantOrgan> organs;   // by label
    int stemLabel = -1;
    std::string stemFoundBy;  // how the stem was told apart, one line

    [[nodiscard]] const PlantOrgan* organ(int label) const;
    [[nodiscard]] const PlantOrgan& stem() const;
    [[nodiscard]] float height_m() const;  // highest point above the foot
};

struct ScannedPlantOptions {
    LengthUnit unit = LengthUnit::Millimetre;
    std::filesystem::path skeleton;  // a skeleton graph; required for a PLY without labels
    // Scans far denser than a depth camera's pixels are thinned to one point per cube of this
    // side (0: kept as read).
    float voxel_m = 0.f;
};

// Throws SynthError naming the file and what is wrong (unreadable, not "x y z label", fewer than
// two organs, no stem to be found, non-finite or absurd coordinates for the unit).
[[nodiscard]] ScannedPlant loadScannedPlant(const std::filesystem::path& file,
                                            const ScannedPlantOptions& options = {});

}  // namespace meadow::synth
