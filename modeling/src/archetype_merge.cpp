#include "meadow/modeling/archetype_merge.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <stdexcept>

namespace meadow::modeling {

namespace {
// Equal arc-length samples for comparing shapes: enough to see a bend or a width bulge.
constexpr int kShapeSamples = 16;
}  // namespace

float shapeDistance_m(const Archetype& a, const Archetype& b) {
    float sum = 0.f;
    for (int i = 0; i < kShapeSamples; ++i) {
        const float s = static_cast<float>(i) / (kShapeSamples - 1);
        const glm::vec3 pa = a.spine_m.at(a.spine_m.parameterAtLengthFraction(s));
        const glm::vec3 pb = b.spine_m.at(b.spine_m.parameterAtLengthFraction(s));
        sum += glm::distance(pa, pb) + std::abs(a.width.at(s) - b.width.at(s));
    }
    return sum / kShapeSamples;
}

void mergeNearDuplicates(ArchetypeLibrary& library, int maxArchetypes) {
    if (maxArchetypes < 1)
        throw std::invalid_argument("mergeNearDuplicates: maxArchetypes must be >= 1");
    auto& items = library.archetypes;
    const std::size_t n = items.size();
    if (n <= static_cast<std::size_t>(maxArchetypes)) return;

    std::vector<std::vector<float>> d(n, std::vector<float>(n, 0.f));
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            d[i][j] = d[j][i] = shapeDistance_m(items[i], items[j]);

    // Complete linkage: the distance of two groups is their farthest pair, so a merged group
    // never holds two blades further apart than the distance recorded for it.
    std::vector<std::vector<std::size_t>> groups(n);
    for (std::size_t i = 0; i < n; ++i) groups[i] = {i};
    const auto linkage = [&](const auto& g, const auto& h) {
        float worst = 0.f;
        for (std::size_t i : g)
            for (std::size_t j : h) worst = std::max(worst, d[i][j]);
        return worst;
    };
    while (groups.size() > static_cast<std::size_t>(maxArchetypes)) {
        std::size_t bi = 0, bj = 1;
        float best = std::numeric_limits<float>::max();
        for (std::size_t i = 0; i < groups.size(); ++i)
            for (std::size_t j = i + 1; j < groups.size(); ++j)
                if (const float l = linkage(groups[i], groups[j]); l < best) {
                    best = l;
                    bi = i;
                    bj = j;
                }
        groups[bi].insert(groups[bi].end(), groups[bj].begin(), groups[bj].end());
        groups.erase(groups.begin() + static_cast<std::ptrdiff_t>(bj));
    }

    std::vector<Archetype> kept;
    for (const auto& g : groups) {
        // The medoid stands for its group: a real captured blade, not an average of several.
        std::size_t medoid = g.front();
        float bestSum = std::numeric_limits<float>::max();
        for (std::size_t i : g) {
            float sum = 0.f;
            for (std::size_t j : g) sum += d[i][j];
            if (sum < bestSum) {
                bestSum = sum;
                medoid = i;
            }
        }
        kept.push_back(items[medoid]);
        if (g.size() > 1) {
            ArchetypeMerge merge{items[medoid].name, {}, linkage(g, g)};
            for (std::size_t i : g)
                if (i != medoid) merge.merged.push_back(items[i].name);
            library.merges.push_back(std::move(merge));
        }
    }
    items = std::move(kept);
}

}  // namespace meadow::modeling
