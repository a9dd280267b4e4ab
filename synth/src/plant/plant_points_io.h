#pragma once
// Reading scanned plants: labelled point text, PLY through PCL, and skeleton graphs
// (scanned_plant.h). Coordinates as in the file, in the file's unit.
#include <filesystem>
#include <glm/vec3.hpp>
#include <utility>
#include <vector>

namespace meadow::synth::plant {

struct LabelledPoints {
    std::vector<glm::vec3> points;
    std::vector<int> labels;  // one per point, or empty when the file carries none
};

// "x y z label" a line; blank lines and lines starting with '#' are skipped.
LabelledPoints readPointText(const std::filesystem::path& file);
// Binary or ascii PLY with x, y, z and an optional integer "label".
LabelledPoints readPointPly(const std::filesystem::path& file);
// By extension: .ply through PCL, anything else as text. Throws SynthError naming the file.
LabelledPoints readLabelledPoints(const std::filesystem::path& file);

struct SkeletonGraph {
    std::vector<glm::vec3> nodes;
    std::vector<int> organ;  // per node: 0 the stem, 1.. a leaf
    std::vector<std::pair<int, int>> edges;
};
// Lines "v x y z organ" and "e i j" (0-based node indices). Throws SynthError naming the file.
SkeletonGraph readSkeletonGraph(const std::filesystem::path& file);

}  // namespace meadow::synth::plant
