#include "upper_distance.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "meadow/modeling/hausdorff.h"

namespace meadow::modeling::detail {

float upperDistance_m(const std::vector<glm::vec3>& a, float lengthA_m,
                      const std::vector<glm::vec3>& b, float lengthB_m, float limit_m) {
    if (a.size() < 2 || b.size() < 2) return std::numeric_limits<float>::infinity();
    const bool aShorter = lengthA_m <= lengthB_m;
    const std::vector<glm::vec3>& from = aShorter ? a : b;
    const std::vector<glm::vec3>& to = aShorter ? b : a;
    const std::size_t first = from.size() / 4;
    const double budget = static_cast<double>(limit_m) * static_cast<double>(from.size() - first);
    // A point's distance to the longer polyline's bounding box bounds its distance to the
    // polyline from below: a cheap first test, and most pairs fail it.
    glm::vec3 lo = to.front(), hi = to.front();
    for (const glm::vec3& p : to) lo = glm::min(lo, p), hi = glm::max(hi, p);
    double bound = 0.0;
    for (std::size_t j = first; j < from.size() && bound <= budget; ++j)
        bound += glm::distance(from[j], glm::clamp(from[j], lo, hi));
    if (bound > budget) return std::numeric_limits<float>::infinity();
    // Both run root to tip, so the nearest segment moves along `to` as j moves along `from`: it is
    // searched for over all of `to` once, then near the last one found.
    constexpr std::size_t kBehind = 4, kAhead = 12;
    double sum = 0.0;
    std::size_t last = 0;
    for (std::size_t j = first; j < from.size(); ++j) {
        const std::size_t begin =
            j == first ? 1 : std::max<std::size_t>(1, last - std::min(last, kBehind));
        const std::size_t end = j == first ? to.size() : std::min(to.size(), last + kAhead);
        float nearest = std::numeric_limits<float>::infinity();
        for (std::size_t k = begin; k < end; ++k)
            if (const float d = pointSegmentDistance_m(from[j], to[k - 1], to[k]); d < nearest)
                nearest = d, last = k;
        sum += nearest;
        if (sum > budget) return std::numeric_limits<float>::infinity();
    }
    return static_cast<float>(sum / static_cast<double>(from.size() - first));
}

}  // namespace meadow::modeling::detail
