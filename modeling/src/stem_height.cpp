#include "meadow/modeling/stem_height.h"

#include <algorithm>
#include <glm/geometric.hpp>

namespace meadow::modeling {

namespace {

// Readings within this many pixels of a point give its depth: the skeleton runs down the
// middle of a stem a few pixels wide, and a single reading there may be missing or mixed.
constexpr int kDepthWindow_px = 3;

std::optional<glm::vec3> backProjected(cv::Point p, const capture::DepthFrame& frame) {
    const cv::Rect window = cv::Rect(p.x - kDepthWindow_px, p.y - kDepthWindow_px,
                                     2 * kDepthWindow_px + 1, 2 * kDepthWindow_px + 1) &
                            cv::Rect({0, 0}, frame.depth_mm.size());
    std::vector<std::uint16_t> read;
    for (int y = window.y; y < window.y + window.height; ++y)
        for (int x = window.x; x < window.x + window.width; ++x)
            if (frame.depth_mm(y, x) > 0) read.push_back(frame.depth_mm(y, x));
    if (read.empty()) return std::nullopt;
    std::nth_element(read.begin(), read.begin() + read.size() / 2, read.end());
    return frame.intrinsics.backProject(static_cast<float>(p.x), static_cast<float>(p.y),
                                        static_cast<float>(read[read.size() / 2]) / 1000.f);
}

}  // namespace

std::optional<float> stemHeight_m(const capture::Segmentation& segmentation,
                                  const capture::DepthFrame& frame) {
    std::optional<float> tallest;
    for (const capture::BladeCluster& cluster : segmentation.clusters) {
        if (cluster.stemLine_px.empty()) continue;
        const auto foot = backProjected(cluster.stemLine_px.front(), frame);
        const auto top = backProjected(cluster.stemLine_px.back(), frame);
        if (!foot || !top) continue;
        const float height = glm::length(*top - *foot);
        if (!tallest || height > *tallest) tallest = height;
    }
    return tallest;
}

std::optional<StemMeasure> stemOf(std::vector<float> heights_m) {
    if (heights_m.empty()) return std::nullopt;
    const auto middle = heights_m.begin() + static_cast<std::ptrdiff_t>(heights_m.size() / 2);
    std::nth_element(heights_m.begin(), middle, heights_m.end());
    return StemMeasure{*middle, static_cast<int>(heights_m.size())};
}

}  // namespace meadow::modeling
