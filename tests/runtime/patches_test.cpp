// Equal-size compact patches (Jahrmann & Wimmer 2017, Sec. 4).
#include "patches.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <glm/common.hpp>
#include <random>

namespace meadow::runtime {
namespace {

TEST(Patches, EqualSizeCompactAndAPermutation) {
    constexpr std::size_t kPatch = 64, kPatches = 64;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.f, 8.f);
    std::vector<glm::vec3> roots;
    for (std::size_t i = 0; i < kPatch * kPatches; ++i) roots.emplace_back(u(rng), 0.f, u(rng));
    const std::vector<float> reach(roots.size(), 0.3f);
    const PatchLayout layout = buildPatches(roots, reach, kPatch);

    ASSERT_EQ(layout.patches.size(), kPatches);
    std::vector<std::uint32_t> sorted = layout.order;
    std::sort(sorted.begin(), sorted.end());
    for (std::uint32_t i = 0; i < sorted.size(); ++i)
        ASSERT_EQ(sorted[i], i) << "order is not a permutation";

    for (std::size_t p = 0; p < layout.patches.size(); ++p) {
        const gpu::PatchGpu& patch = layout.patches[p];
        EXPECT_EQ(patch.range.y, kPatch);
        EXPECT_EQ(patch.range.x, p * kPatch);
        EXPECT_EQ(patch.range.y % BLADE_WORKGROUP_SIZE, 0u);
        // Compact: 64 patches tile 64 m^2, so a balanced split gives ~1 m^2 boxes (+ reach).
        glm::vec3 lo(1e9f), hi(-1e9f);
        for (std::uint32_t i = patch.range.x; i < patch.range.x + patch.range.y; ++i) {
            lo = glm::min(lo, roots[layout.order[i]]);
            hi = glm::max(hi, roots[layout.order[i]]);
            // The box holds every pose the blade can reach.
            for (int k = 0; k < 3; ++k) {
                EXPECT_LE(patch.boundsMin_m[k], roots[layout.order[i]][k] - reach[0] + 1e-5f);
                EXPECT_GE(patch.boundsMax_m[k], roots[layout.order[i]][k] + reach[0] - 1e-5f);
            }
        }
        EXPECT_LT((hi.x - lo.x) * (hi.z - lo.z), 2.f)
            << "patch " << p << " spans " << hi.x - lo.x << " x " << hi.z - lo.z << " m";
        EXPECT_LT(std::max(hi.x - lo.x, hi.z - lo.z), 2.f) << "patch " << p << " is not compact";
    }
}

TEST(Patches, RejectsACountThatIsNotAMultipleOfThePatchSize) {
    EXPECT_THROW(buildPatches(std::vector<glm::vec3>(65), std::vector<float>(65), 64),
                 std::invalid_argument);
}

}  // namespace
}  // namespace meadow::runtime
