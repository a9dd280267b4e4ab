#pragma once
// The organs of a scanned plant from its labelled points (scanned_plant.h): which one is the
// stem, which way is up, and each organ's centre line, length and width.
#include <glm/vec3.hpp>
#include <string>
#include <vector>

namespace meadow::synth::plant {

struct OrganPoints {
    int label = 0;
    std::vector<glm::vec3> points;
};
// One entry per label, in increasing label order.
std::vector<OrganPoints> groupByOrgan(const std::vector<glm::vec3>& points,
                                      const std::vector<int>& labels);

// Median distance of a point to its nearest neighbour: the scan's point spacing.
float pointSpacing_m(const std::vector<glm::vec3>& points);

struct StemChoice {
    int label = -1;
    std::string reason;  // one line: how it was told apart
};
// Leaves leave the stem (a grass leaf's sheath wraps it), so the stem is the organ that touches
// the most others, within contact_m; a tie goes to the roundest cross-section (the smallest
// covariance eigenvalue over the middle one: a stem is a cylinder, a leaf a sheet).
StemChoice findStem(const std::vector<OrganPoints>& organs, float contact_m);

struct StemAxis {
    glm::vec3 up{0.f, 1.f, 0.f};  // unit
    glm::vec3 foot{0.f};          // where the axis leaves the stem's lowest points
};
// The stem's principal axis, pointing toward the plant's mass (leaves reach above the foot of
// the stem); the foot is the axis at the stem's lowest percent of points.
StemAxis stemAxis(const std::vector<glm::vec3>& stem, const std::vector<glm::vec3>& all);

struct CentreLine {
    std::vector<glm::vec3> line;  // base to tip
    float length_m = 0.f;
    float maxWidth_m = 0.f;
};
// A leaf's centre line: shortest paths over the leaf's nearest-neighbour graph from its point
// nearest the stem, the points binned by that distance, each bin's centroid a vertex; the width
// is the 5-95 % spread of a bin across the line over 0.9 (that spread of an even spread of
// points), the widest bin beyond the first tenth of the length (the sheath wraps the stem there).
CentreLine leafCentreLine(const std::vector<glm::vec3>& leaf, const std::vector<glm::vec3>& stem,
                          float spacing_m);
// The same along a given line (a skeleton graph's): only the width is measured.
CentreLine leafAlongLine(const std::vector<glm::vec3>& leaf, std::vector<glm::vec3> line);
// The stem from its foot up its axis; the width is twice its median distance from the axis.
CentreLine stemCentreLine(const std::vector<glm::vec3>& stem, const StemAxis& axis);

}  // namespace meadow::synth::plant
