#include "patches.h"

#include <algorithm>
#include <glm/common.hpp>
#include <limits>
#include <stdexcept>
#include <string>

namespace meadow::runtime {
namespace {

// Morton code of a point quantised to 10 bits per axis inside a box.
constexpr float kMortonCells = 1023.f;

std::uint32_t spreadBits10(std::uint32_t x) {
    x &= 0x3ffu;
    x = (x | (x << 16)) & 0x030000ffu;
    x = (x | (x << 8)) & 0x0300f00fu;
    x = (x | (x << 4)) & 0x030c30c3u;
    x = (x | (x << 2)) & 0x09249249u;
    return x;
}

struct Builder {
    const std::vector<glm::vec3>& roots;
    const std::vector<float>& reach;
    std::size_t patchSize;
    std::vector<std::uint32_t>& order;
    std::vector<gpu::PatchGpu>& patches;

    void box(std::size_t begin, std::size_t end, glm::vec3& lo, glm::vec3& hi) const {
        lo = glm::vec3(std::numeric_limits<float>::max());
        hi = -lo;
        for (std::size_t i = begin; i < end; ++i) {
            lo = glm::min(lo, roots[order[i]]);
            hi = glm::max(hi, roots[order[i]]);
        }
    }

    void leaf(std::size_t begin, std::size_t end) {
        glm::vec3 lo, hi;
        box(begin, end, lo, hi);
        const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-6f));
        auto morton = [&](std::uint32_t b) {
            const glm::uvec3 q = glm::uvec3((roots[b] - lo) / extent * kMortonCells);
            return spreadBits10(q.x) | (spreadBits10(q.y) << 1) | (spreadBits10(q.z) << 2);
        };
        std::stable_sort(order.begin() + static_cast<std::ptrdiff_t>(begin),
                         order.begin() + static_cast<std::ptrdiff_t>(end),
                         [&](std::uint32_t a, std::uint32_t b) { return morton(a) < morton(b); });
        glm::vec3 reachLo(std::numeric_limits<float>::max()),
            reachHi(-std::numeric_limits<float>::max());
        for (std::size_t i = begin; i < end; ++i) {
            reachLo = glm::min(reachLo, roots[order[i]] - glm::vec3(reach[order[i]]));
            reachHi = glm::max(reachHi, roots[order[i]] + glm::vec3(reach[order[i]]));
        }
        gpu::PatchGpu p{};
        p.boundsMin_m = glm::vec4(reachLo, 0.f);
        p.boundsMax_m = glm::vec4(reachHi, 0.f);
        p.range = glm::uvec4(static_cast<std::uint32_t>(begin),
                             static_cast<std::uint32_t>(end - begin), 0u, 0u);
        patches.push_back(p);
    }

    void split(std::size_t begin, std::size_t end) {
        const std::size_t count = end - begin;
        if (count <= patchSize) return leaf(begin, end);
        glm::vec3 lo, hi;
        box(begin, end, lo, hi);
        const glm::vec3 extent = hi - lo;
        const int axis =
            extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        // The split falls on a patch boundary: half of the patches (rounded down) go left.
        const std::size_t mid = begin + (count / patchSize / 2) * patchSize;
        std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin),
                         order.begin() + static_cast<std::ptrdiff_t>(mid),
                         order.begin() + static_cast<std::ptrdiff_t>(end),
                         [&](std::uint32_t a, std::uint32_t b) {
                             return roots[a][axis] < roots[b][axis] ||
                                    (roots[a][axis] == roots[b][axis] && a < b);
                         });
        split(begin, mid);
        split(mid, end);
    }
};

}  // namespace

PatchLayout buildPatches(const std::vector<glm::vec3>& roots_m, const std::vector<float>& reach_m,
                         std::size_t patchSize) {
    if (patchSize == 0 || roots_m.size() != reach_m.size() || roots_m.empty() ||
        roots_m.size() % patchSize != 0)
        throw std::invalid_argument(
            "buildPatches: need roots.size() == reach.size() == a positive multiple of "
            "patchSize, got " +
            std::to_string(roots_m.size()) + ", " + std::to_string(reach_m.size()) + ", " +
            std::to_string(patchSize));
    PatchLayout layout;
    layout.order.resize(roots_m.size());
    for (std::uint32_t i = 0; i < layout.order.size(); ++i) layout.order[i] = i;
    Builder{roots_m, reach_m, patchSize, layout.order, layout.patches}.split(0, roots_m.size());
    return layout;
}

}  // namespace meadow::runtime
