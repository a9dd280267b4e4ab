// Points along an open polyline by arc length (polyline.h).
#include "segmentation/polyline.h"

#include <cmath>
#include <opencv2/core.hpp>

namespace meadow::capture::segmentation {
namespace {

// The points at arc lengths arcAt(0) <= arcAt(1) <= ... (each within the line's length), by
// walking the segments once.
template <typename ArcAt>
std::vector<cv::Point2f> pointsAtArcLengths(const std::vector<cv::Point2f>& line,
                                            const std::vector<float>& arc, int count, ArcAt arcAt) {
    std::vector<cv::Point2f> out;
    out.reserve(static_cast<size_t>(count));
    size_t j = 0;
    for (int k = 0; k < count; ++k) {
        const float s = arcAt(k);
        while (j + 1 < line.size() && arc[j + 1] < s) ++j;
        if (j + 1 >= line.size()) {
            out.push_back(line.back());
            continue;
        }
        const float seg = arc[j + 1] - arc[j];
        const float t = seg > 0.f ? (s - arc[j]) / seg : 0.f;
        out.push_back(line[j] + t * (line[j + 1] - line[j]));
    }
    return out;
}

std::vector<float> arcLengths(const std::vector<cv::Point2f>& line) {
    std::vector<float> arc(line.size(), 0.f);
    for (size_t i = 1; i < line.size(); ++i)
        arc[i] = arc[i - 1] + static_cast<float>(cv::norm(line[i] - line[i - 1]));
    return arc;
}

}  // namespace

std::vector<cv::Point2f> resampledEvenly(const std::vector<cv::Point2f>& line, int count) {
    if (line.empty()) return {};
    const auto arc = arcLengths(line);
    const float total = arc.back();
    return pointsAtArcLengths(line, arc, count, [&](int k) {
        return total * static_cast<float>(k) / static_cast<float>(count - 1);
    });
}

std::vector<cv::Point2f> resampledEvery(const std::vector<cv::Point2f>& line, float step_px) {
    if (line.empty()) return {};
    const auto arc = arcLengths(line);
    const int count = static_cast<int>(std::floor(arc.back() / step_px)) + 1;
    return pointsAtArcLengths(line, arc, count,
                              [&](int k) { return step_px * static_cast<float>(k); });
}

}  // namespace meadow::capture::segmentation
