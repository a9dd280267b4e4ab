#pragma once
// Test support, header-only: a plant of known organs written as "x y z label" text in millimetres,
// standing along the file's +Z (so reading it must find up): a stem (a cylinder of points,
// label 1) and two arching leaves (ribbons of points, labels 2 and 3) leaving it at known
// heights, with their true lengths and widths.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <numbers>

namespace meadow::test {

struct MadeLeaf {
    int label = 0;
    float attach_m = 0.f;                            // height on the stem where it leaves it
    float side = 1.f;                                // +1 toward +X, -1 toward -X
    float reach_m = 0.f;                             // how far out it reaches
    float rise_m = 0.f;                              // how far up it rises before it arches down
    float width_m = 0.02f;                           // widest, at its middle 80 %
    [[nodiscard]] glm::vec3 centre(float t) const {  // t in [0, 1], file coordinates (Z up), m
        return {side * (kStemRadius_m + reach_m * t), 0.f,
                attach_m + rise_m * (2.f * t - 1.6f * t * t)};
    }
    [[nodiscard]] float length_m() const {
        float l = 0.f;
        for (int i = 1; i <= 1000; ++i)
            l += glm::distance(centre(static_cast<float>(i) / 1000.f),
                               centre(static_cast<float>(i - 1) / 1000.f));
        return l;
    }
    static constexpr float kStemRadius_m = 0.006f;
};

inline constexpr float kMadeStemHeight_m = 0.15f;
inline const MadeLeaf kMadeLeaves[] = {{2, 0.05f, 1.f, 0.22f, 0.12f, 0.02f},
                                       {3, 0.10f, -1.f, 0.16f, 0.08f, 0.016f}};

// Writes the plant; returns the file.
inline std::filesystem::path writeMadePlant(const std::filesystem::path& file) {
    std::ofstream out(file);
    out << "# a made plant: stem label 1, leaves 2 and 3, millimetres, Z up\n";
    const auto put = [&](glm::vec3 p, int label) {
        out << p.x * 1000.f << ' ' << p.y * 1000.f << ' ' << p.z * 1000.f << ' ' << label << '\n';
    };
    for (int h = 0; h <= 75; ++h)
        for (int a = 0; a < 12; ++a) {
            const float phi = 2.f * std::numbers::pi_v<float> * static_cast<float>(a) / 12.f;
            put({MadeLeaf::kStemRadius_m * std::cos(phi), MadeLeaf::kStemRadius_m * std::sin(phi),
                 kMadeStemHeight_m * static_cast<float>(h) / 75.f},
                1);
        }
    for (const MadeLeaf& leaf : kMadeLeaves)
        for (int i = 0; i <= 200; ++i) {
            const float t = static_cast<float>(i) / 200.f;
            const float w = leaf.width_m * std::min({1.f, t / 0.1f + 0.3f, (1.f - t) / 0.1f});
            for (int j = 0; j < 9; ++j)
                put(leaf.centre(t) + glm::vec3(0.f, w * (static_cast<float>(j) / 8.f - 0.5f), 0.f),
                    leaf.label);
        }
    return file;
}

}  // namespace meadow::test
