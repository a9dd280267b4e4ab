#include "meadow/modeling/archetype_merge.h"

#include <gtest/gtest.h>

#include <algorithm>

using namespace meadow::modeling;

namespace {
Archetype blade(const std::string& name, float tipX_m, float height_m, float width_m) {
    Archetype a;
    a.name = name;
    a.spine_m = {{0, 0, 0}, {0, height_m * 0.5f, 0}, {tipX_m, height_m, 0}};
    a.width.width_m = {width_m, width_m * 0.6f, 0.f};
    return a;
}
}  // namespace

TEST(ArchetypeMerge, ShapeDistanceIsZeroForIdenticalAndGrowsWithTheDifference) {
    const Archetype a = blade("a", 0.02f, 0.2f, 0.01f);
    EXPECT_FLOAT_EQ(shapeDistance_m(a, a), 0.f);
    const float near = shapeDistance_m(a, blade("b", 0.025f, 0.2f, 0.01f));
    const float far = shapeDistance_m(a, blade("c", 0.08f, 0.2f, 0.01f));
    EXPECT_GT(near, 0.f);
    EXPECT_GT(far, 3.f * near);
}

TEST(ArchetypeMerge, MergesTheNearDuplicatesAndRecordsWhatWasFolded) {
    ArchetypeLibrary lib;
    // Two families: three nearly identical short leaves and two nearly identical tall grasses.
    lib.archetypes = {
        blade("leaf-1", 0.030f, 0.12f, 0.015f), blade("grass-1", 0.01f, 0.30f, 0.004f),
        blade("leaf-2", 0.032f, 0.12f, 0.015f), blade("leaf-3", 0.028f, 0.121f, 0.016f),
        blade("grass-2", 0.012f, 0.30f, 0.004f)};
    mergeNearDuplicates(lib, 2);
    ASSERT_EQ(lib.archetypes.size(), 2u);
    ASSERT_EQ(lib.merges.size(), 2u);
    std::size_t folded = 0;
    for (const auto& m : lib.merges) {
        folded += m.merged.size();
        const bool leaves = m.kept.rfind("leaf", 0) == 0;
        for (const auto& name : m.merged)
            EXPECT_EQ(name.rfind(leaves ? "leaf" : "grass", 0), 0u)
                << "a family was mixed: " << name;
        EXPECT_LT(m.shapeDistance_m, 0.005f);
    }
    EXPECT_EQ(folded, 3u);
    // The medoid stands for each group: leaf-1 lies between leaf-2 and leaf-3; the two grasses
    // tie, and the first one stays.
    std::vector<std::string> names;
    for (const auto& a : lib.archetypes) names.push_back(a.name);
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"grass-1", "leaf-1"}));
}

TEST(ArchetypeMerge, LeavesASmallEnoughLibraryAlone) {
    ArchetypeLibrary lib;
    lib.archetypes = {blade("a", 0.f, 0.1f, 0.01f), blade("b", 0.05f, 0.2f, 0.01f)};
    mergeNearDuplicates(lib, 5);
    EXPECT_EQ(lib.archetypes.size(), 2u);
    EXPECT_TRUE(lib.merges.empty());
    EXPECT_THROW(mergeNearDuplicates(lib, 0), std::invalid_argument);
}
