// The shared GLSL/C++ header compiles as C++ and gives std430 layouts (style.md §6).
#include <gtest/gtest.h>

#include <cstddef>

#include "shared/blade_types.h"

namespace meadow::runtime::gpu {
namespace {

TEST(BladeLayout, BladeIsFourVec4sInPaperOrder) {
    EXPECT_EQ(sizeof(BladeGpu), 64u);
    EXPECT_EQ(offsetof(BladeGpu, v0_height), 0u);
    EXPECT_EQ(offsetof(BladeGpu, v1_width), 16u);
    EXPECT_EQ(offsetof(BladeGpu, v2_stiffness), 32u);
    EXPECT_EQ(offsetof(BladeGpu, up_direction), 48u);
}

TEST(BladeLayout, Std430SizesOfEveryBufferStruct) {
    EXPECT_EQ(sizeof(BladeRestGpu), 32u);
    EXPECT_EQ(sizeof(ArchetypeGpu), 16u * (ARCHETYPE_WIDTH_SAMPLES / 4 + 2));
    EXPECT_EQ(offsetof(ArchetypeGpu, shape), 16u * (ARCHETYPE_WIDTH_SAMPLES / 4));
    EXPECT_EQ(offsetof(ArchetypeGpu, sides), 16u * (ARCHETYPE_WIDTH_SAMPLES / 4 + 1));
    EXPECT_EQ(sizeof(DrawCommandGpu), 4u * sizeof(std::uint32_t))
        << "glDrawArraysIndirect reads four uints";
    EXPECT_EQ(sizeof(PatchGpu), 48u);
    EXPECT_EQ(offsetof(PatchGpu, range), 32u);
    EXPECT_EQ(sizeof(ColliderGpu), 16u);
    EXPECT_EQ(offsetof(FrameGpu, clipFromWorld), 64u);
    EXPECT_EQ(offsetof(FrameGpu, wind), 176u);
}

TEST(BladeLayout, WidthSamplesFillWholeVec4sAndWorkgroupIsAWarpMultiple) {
    EXPECT_EQ(ARCHETYPE_WIDTH_SAMPLES % 4, 0);
    EXPECT_EQ(BLADE_WORKGROUP_SIZE % 32, 0);
}

TEST(BladeLayout, BindingPointsAreDistinct) {
    const int bindings[] = {BLADE_SSBO_BINDING,        BLADE_REST_SSBO_BINDING,
                            ARCHETYPE_SSBO_BINDING,    VISIBLE_INDEX_SSBO_BINDING,
                            DRAW_COMMAND_SSBO_BINDING, CULL_STATS_SSBO_BINDING,
                            PATCH_SSBO_BINDING,        COLLIDER_SSBO_BINDING};
    for (std::size_t i = 0; i < std::size(bindings); ++i)
        for (std::size_t j = i + 1; j < std::size(bindings); ++j)
            EXPECT_NE(bindings[i], bindings[j]);
}

}  // namespace
}  // namespace meadow::runtime::gpu
