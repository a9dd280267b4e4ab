#include "ground_maps.h"

#include <algorithm>
#include <opencv2/imgcodecs.hpp>

#include "meadow/core/library_messages.h"
#include "meadow/runtime/error.h"

namespace meadow::runtime {

cv::Point texelAt(const GroundImage& extent, cv::Size size, glm::vec3 p_m) {
    const float fx = (p_m.x - extent.minXZ_m.x) / (extent.maxXZ_m.x - extent.minXZ_m.x);
    const float fz = (p_m.z - extent.minXZ_m.y) / (extent.maxXZ_m.y - extent.minXZ_m.y);
    const int col = std::clamp(static_cast<int>(fx * static_cast<float>(size.width - 1) + 0.5f), 0,
                               size.width - 1);
    const int row = std::clamp(static_cast<int>(fz * static_cast<float>(size.height - 1) + 0.5f), 0,
                               size.height - 1);
    return {col, row};
}

namespace {
cv::Mat readDensityImage(const DensityMap& map) {
    const CapturedStderr quiet;  // libpng's words on a corrupt image: the error below says it
    return cv::imread(map.image.string(), cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH);
}
std::string unreadableDensityMap(const DensityMap& map) {
    return "density map " + map.image.string() +
           " is not a readable image; give an 8- or 16-bit grey PNG";
}
}  // namespace

std::string densityMapProblem(const DensityMap& map) {
    return readDensityImage(map).empty() ? unreadableDensityMap(map) : std::string();
}

cv::Mat loadDensityMap(const DensityMap& map) {
    const cv::Mat image = readDensityImage(map);
    if (image.empty()) throw RuntimeError(unreadableDensityMap(map));
    cv::Mat density;
    image.convertTo(density, CV_32F, image.depth() == CV_16U ? 1.0 / 65535.0 : 1.0 / 255.0);
    return density;
}

ArchetypeMapImage readArchetypeMap(const ArchetypeMap& map, std::size_t archetypeCount) {
    const std::string name = "archetype map " + map.image.string();
    const std::string wanted = "give an 8-bit grey PNG whose values are archetype indices 0.." +
                               std::to_string(archetypeCount - 1) + " (" +
                               std::to_string(kArchetypeByWeights) + ": by weights)";
    // IMREAD_UNCHANGED: a 16-bit or colour image is an error, not something to convert, because
    // converting would silently turn indices into other indices.
    cv::Mat image;
    {
        const CapturedStderr quiet;  // libpng's words on a corrupt image: the error says it
        image = cv::imread(map.image.string(), cv::IMREAD_UNCHANGED);
    }
    if (image.empty()) return {{}, name + " is not a readable image; " + wanted};
    if (image.depth() != CV_8U || image.channels() != 1) {
        const int bits = image.depth() == CV_16U ? 16 : image.depth() == CV_8U ? 8 : 32;
        return {{},
                name + " is " + std::to_string(bits) + "-bit with " +
                    std::to_string(image.channels()) + " channel(s); " + wanted};
    }
    for (int row = 0; row < image.rows; ++row)
        for (int col = 0; col < image.cols; ++col) {
            const std::uint8_t k = image.at<std::uint8_t>(row, col);
            if (k < archetypeCount || k == kArchetypeByWeights) continue;
            return {{},
                    name + " has value " + std::to_string(k) + " at column " + std::to_string(col) +
                        ", row " + std::to_string(row) + ", but the scene has " +
                        std::to_string(archetypeCount) + " archetypes; " + wanted};
        }
    return {image, ""};
}

cv::Mat loadArchetypeMap(const ArchetypeMap& map, std::size_t archetypeCount) {
    ArchetypeMapImage m = readArchetypeMap(map, archetypeCount);
    if (!m.problem.empty()) throw RuntimeError(m.problem);
    return m.indices;
}

}  // namespace meadow::runtime
