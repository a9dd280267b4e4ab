// Refined Hausdorff distance (Fan & Sheng 2017, Algorithm 2) and polyline Hausdorff distances.
#include "meadow/modeling/hausdorff.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <limits>
#include <stdexcept>
#include <string>

namespace meadow::modeling {
namespace {

float pointPolylineDistance_m(const glm::vec3& p, const std::vector<glm::vec3>& line) {
    if (line.size() == 1) return glm::distance(p, line.front());
    float best = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i + 1 < line.size(); ++i)
        best = std::min(best, pointSegmentDistance_m(p, line[i], line[i + 1]));
    return best;
}

void checkKept(const std::vector<int>& kept, std::size_t n) {
    for (std::size_t i = 0; i < kept.size(); ++i) {
        if (kept[i] < 0 || static_cast<std::size_t>(kept[i]) >= n ||
            (i > 0 && kept[i] <= kept[i - 1]))
            throw std::invalid_argument("kept knot indices must be ascending and in [0, " +
                                        std::to_string(n) + "); entry " + std::to_string(i) +
                                        " is " + std::to_string(kept[i]));
    }
    if (kept.empty()) throw std::invalid_argument("kept knot indices are empty");
}

}  // namespace

float pointSegmentDistance_m(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 ab = b - a;
    const float len2 = glm::dot(ab, ab);
    const float t = len2 > 0.f ? std::clamp(glm::dot(p - a, ab) / len2, 0.f, 1.f) : 0.f;
    return glm::distance(p, a + t * ab);
}

float refinedHausdorff_m(const std::vector<glm::vec3>& knots, const std::vector<int>& kept) {
    checkKept(kept, knots.size());
    float worst = 0.f;
    std::size_t k = 0;
    for (std::size_t i = 0; i < knots.size(); ++i) {
        if (k < kept.size() && static_cast<std::size_t>(kept[k]) == i) {
            ++k;
            continue;
        }
        // Algorithm 2: a culled knot is represented by its nearest kept knot.
        float nearest = std::numeric_limits<float>::max();
        for (int j : kept) nearest = std::min(nearest, glm::distance(knots[i], knots[j]));
        worst = std::max(worst, nearest);
    }
    return worst;
}

float directedHausdorff_m(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to,
                          int samplesPerSegment) {
    if (from.empty() || to.empty())
        throw std::invalid_argument("directedHausdorff_m: empty polyline");
    if (samplesPerSegment < 1)
        throw std::invalid_argument("directedHausdorff_m: samplesPerSegment must be >= 1");
    float worst = pointPolylineDistance_m(from.front(), to);
    for (std::size_t i = 0; i + 1 < from.size(); ++i)
        for (int s = 1; s <= samplesPerSegment; ++s) {
            const float f = static_cast<float>(s) / static_cast<float>(samplesPerSegment);
            worst =
                std::max(worst, pointPolylineDistance_m(from[i] + f * (from[i + 1] - from[i]), to));
        }
    return worst;
}

float hausdorff_m(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b,
                  int samplesPerSegment) {
    return std::max(directedHausdorff_m(a, b, samplesPerSegment),
                    directedHausdorff_m(b, a, samplesPerSegment));
}

RefinementError evaluateRefinement(const KnotTrajectories& frames, const std::vector<int>& kept) {
    if (frames.empty()) throw std::invalid_argument("evaluateRefinement: no frames");
    RefinementError e;
    std::vector<glm::vec3> refined(kept.size());
    for (const std::vector<glm::vec3>& knots : frames) {
        const float rh = refinedHausdorff_m(knots, kept);
        e.refinedHausdorffMean_m += rh;
        e.refinedHausdorffMax_m = std::max(e.refinedHausdorffMax_m, rh);
        for (std::size_t i = 0; i < kept.size(); ++i) refined[i] = knots[kept[i]];
        e.hausdorffMax_m = std::max(e.hausdorffMax_m, hausdorff_m(knots, refined));
    }
    e.refinedHausdorffMean_m /= static_cast<float>(frames.size());
    e.maxDeviation_m = maxDeviation_m(frames, kept);
    return e;
}

float maxDeviation_m(const KnotTrajectories& frames, const std::vector<int>& kept) {
    if (frames.empty()) throw std::invalid_argument("maxDeviation_m: no frames");
    float worst = 0.f;
    std::vector<glm::vec3> refined(kept.size());
    for (const std::vector<glm::vec3>& knots : frames) {
        for (std::size_t i = 0; i < kept.size(); ++i) refined[i] = knots[kept[i]];
        for (const glm::vec3& p : knots)
            worst = std::max(worst, pointPolylineDistance_m(p, refined));
    }
    return worst;
}

}  // namespace meadow::modeling
