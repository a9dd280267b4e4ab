// Points along an open polyline by arc length (polyline.h).
#include "segmentation/polyline.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

float quadraticBezierMiss_px(const std::vector<cv::Point2f>& line) {
    if (line.size() < 3) return 0.f;
    std::vector<float> t(line.size(), 0.f);
    for (std::size_t i = 1; i < line.size(); ++i)
        t[i] = t[i - 1] + static_cast<float>(cv::norm(line[i] - line[i - 1]));
    if (!(t.back() > 0.f)) return 0.f;
    for (float& ti : t) ti /= t.back();
    const cv::Point2f p0 = line.front(), p2 = line.back();
    constexpr int kCurveSamples = 256;
    std::vector<cv::Point2f> curve(kCurveSamples + 1);
    float worst = 0.f;
    // Least squares for p1 at the points' parameters, then each point's parameter moved to its
    // nearest point of the curve (Hoschek's parameter correction), a few times: chord-length
    // parameters alone misplace the points of a strongly bent line.
    constexpr int kCorrections = 6;
    for (int round = 0; round <= kCorrections; ++round) {
        // B(t) = (1-t)^2 p0 + 2 t (1-t) p1 + t^2 p2 is linear in p1: the best p1 is closed form.
        cv::Point2f numerator(0.f, 0.f);
        float denominator = 0.f;
        for (std::size_t i = 0; i < line.size(); ++i) {
            const float b0 = (1 - t[i]) * (1 - t[i]), b1 = 2 * t[i] * (1 - t[i]), b2 = t[i] * t[i];
            numerator += b1 * (line[i] - b0 * p0 - b2 * p2);
            denominator += b1 * b1;
        }
        const cv::Point2f p1 = denominator > 0.f ? numerator / denominator : 0.5f * (p0 + p2);
        for (int k = 0; k <= kCurveSamples; ++k) {
            const float u = static_cast<float>(k) / kCurveSamples;
            curve[static_cast<std::size_t>(k)] =
                (1 - u) * (1 - u) * p0 + 2 * u * (1 - u) * p1 + u * u * p2;
        }
        worst = 0.f;
        for (std::size_t i = 0; i < line.size(); ++i) {
            float nearest = std::numeric_limits<float>::max();
            for (int k = 0; k <= kCurveSamples; ++k) {
                const float d =
                    static_cast<float>(cv::norm(line[i] - curve[static_cast<std::size_t>(k)]));
                if (d < nearest) {
                    nearest = d;
                    t[i] = static_cast<float>(k) / kCurveSamples;
                }
            }
            worst = std::max(worst, nearest);
        }
        t.front() = 0.f;  // the ends stay on the end points
        t.back() = 1.f;
    }
    return worst;
}

}  // namespace meadow::capture::segmentation
