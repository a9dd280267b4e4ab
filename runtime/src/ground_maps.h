#pragma once
// Images laid over the world's XZ plane (docs/formats.md#scene): the density map
// (blades.density_map) and the archetype map (archetypes.map). Both use one coordinate mapping:
// column 0 at min x, the last column at max x, row 0 at min z, the last row at max z, nearest
// texel, points outside clamped to the border.
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <opencv2/core/mat.hpp>
#include <string>

#include "meadow/runtime/scene.h"

namespace meadow::runtime {

// Archetype map value that leaves the choice to archetypes.weights.
inline constexpr std::uint8_t kArchetypeByWeights = 255;

// The texel (x = column, y = row) nearest to world point p on a map of `size` over `extent`.
cv::Point texelAt(const GroundImage& extent, cv::Size size, glm::vec3 p_m);

// CV_32F in [0, 1] from an 8- or 16-bit grey image. Throws RuntimeError when unreadable.
cv::Mat loadDensityMap(const DensityMap& map);
// Empty when the density map's image reads, else one line naming it and what to do.
std::string densityMapProblem(const DensityMap& map);

struct ArchetypeMapImage {
    cv::Mat indices;      // CV_8UC1; empty when `problem` is set
    std::string problem;  // empty, or one line naming the image and what to do
};
// Reads an archetype map and checks it: an 8-bit single-channel image whose every value is an
// archetype index below `archetypeCount` or kArchetypeByWeights.
ArchetypeMapImage readArchetypeMap(const ArchetypeMap& map, std::size_t archetypeCount);
// readArchetypeMap, throwing RuntimeError on a problem.
cv::Mat loadArchetypeMap(const ArchetypeMap& map, std::size_t archetypeCount);

}  // namespace meadow::runtime
