#pragma once
// Resampling of a skeleton's per-point sequences by 3D arc length (blade_root.cpp, blade_tip.cpp):
// stations are computed once on the points, then every sequence is sampled at them. And the
// polyline's length (blade_root.cpp, blade_tracks.cpp).
#include <algorithm>
#include <cstddef>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <utility>
#include <vector>

namespace meadow::modeling::detail {

// Length of a polyline (0 for fewer than two points).
inline float polylineLength_m(const std::vector<glm::vec3>& p) {
    float length = 0.f;
    for (std::size_t i = 1; i < p.size(); ++i) length += glm::distance(p[i - 1], p[i]);
    return length;
}

// Position (segment index, fraction) of n points evenly spaced by arc length along a polyline.
inline std::vector<std::pair<std::size_t, float>> arcLengthStations(const std::vector<glm::vec3>& p,
                                                                    int n) {
    std::vector<float> cumulative(p.size(), 0.f);
    for (std::size_t i = 1; i < p.size(); ++i)
        cumulative[i] = cumulative[i - 1] + glm::distance(p[i - 1], p[i]);
    std::vector<std::pair<std::size_t, float>> out;
    std::size_t seg = 0;
    for (int k = 0; k < n; ++k) {
        const float target = cumulative.back() * static_cast<float>(k) / static_cast<float>(n - 1);
        while (seg + 2 < p.size() && cumulative[seg + 1] < target) ++seg;
        const float len = cumulative[seg + 1] - cumulative[seg];
        out.emplace_back(seg,
                         len > 0.f ? std::clamp((target - cumulative[seg]) / len, 0.f, 1.f) : 0.f);
    }
    return out;
}

template <class T>
std::vector<T> sampleAt(const std::vector<T>& v,
                        const std::vector<std::pair<std::size_t, float>>& stations) {
    std::vector<T> out;
    out.reserve(stations.size());
    for (const auto& [i, f] : stations) out.push_back(v[i] + f * (v[i + 1] - v[i]));
    return out;
}

}  // namespace meadow::modeling::detail
