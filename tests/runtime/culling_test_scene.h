#pragma once
// A synthetic culling scene shared by the CPU and GPU culling tests: a 48 m x 48 m meadow of
// locality-sorted 4 m x 4 m patches (144 patches of 64 blades), a camera standing at its edge,
// and an opaque "wall" in the depth pre-pass covering the right third of the image 6 m away.
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <vector>

#include "culling_reference.h"
#include "physics_reference.h"

namespace meadow::runtime::testing {

struct CullScene {
    std::vector<gpu::BladeGpu> blades;
    std::vector<gpu::PatchGpu> patches;
    glm::mat4 clipFromWorld{1.f};
    glm::vec3 camera_m{0.f};
    float near_m = 0.1f, far_m = 100.f;
    std::uint32_t depthWidth = 64, depthHeight = 48;
    std::vector<float> depth;  // window depth, row 0 at the bottom
};

inline float windowDepthAt(float viewDistance_m, float near_m, float far_m) {
    // Inverse of viewDepth_m(): z = far (d - near) / (d (far - near)).
    return far_m * (viewDistance_m - near_m) / (viewDistance_m * (far_m - near_m));
}

inline CullScene makeCullScene(std::uint32_t seed) {
    CullScene s;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.f, 1.f);
    constexpr int kPatchesPerSide = 12, kBladesPerPatch = 64;
    constexpr float kPatch_m = 4.f;
    for (int pz = 0; pz < kPatchesPerSide; ++pz)
        for (int px = 0; px < kPatchesPerSide; ++px) {
            const glm::vec3 corner{(px - kPatchesPerSide / 2) * kPatch_m, 0.f,
                                   (pz - kPatchesPerSide / 2) * kPatch_m};
            gpu::PatchGpu patch{};
            patch.range =
                glm::uvec4(static_cast<std::uint32_t>(s.blades.size()), kBladesPerPatch, 0, 0);
            float maxH = 0.f;
            for (int i = 0; i < kBladesPerPatch; ++i) {
                const glm::vec3 v0 =
                    corner + glm::vec3(kPatch_m * unit(rng), 0.f, kPatch_m * unit(rng));
                const glm::vec3 up{0.f, 1.f, 0.f};
                const float h = 0.3f + 0.5f * unit(rng);
                const float angle = 6.2831853f * unit(rng);
                const glm::vec3 f = shader::bladeFrontDirection(up, angle);
                const glm::vec3 tip = v0 + h * glm::normalize(up + 0.6f * unit(rng) * f);
                const ValidatedCurve c = validateBladeReference(
                    v0, tip, up, h,
                    shader::middleControlPoint(v0, up, h, shader::projectedLength(v0, tip, up)),
                    tip, PHYSICS_LENGTH_EXACT);
                s.blades.push_back({glm::vec4(v0, h), glm::vec4(c.v1, 0.01f), glm::vec4(c.v2, 10.f),
                                    glm::vec4(up, angle)});
                maxH = std::max(maxH, h);
            }
            patch.boundsMin_m = glm::vec4(corner - glm::vec3(maxH, 0.f, maxH), 0.f);
            patch.boundsMax_m =
                glm::vec4(corner + glm::vec3(kPatch_m + maxH, maxH, kPatch_m + maxH), 0.f);
            s.patches.push_back(patch);
        }
    s.camera_m = {2.f, 1.7f, 20.f};
    const glm::mat4 viewFromWorld =
        glm::lookAt(s.camera_m, glm::vec3(-2.f, 0.f, 0.f), {0.f, 1.f, 0.f});
    const glm::mat4 clipFromView =
        glm::perspective(glm::radians(60.f), 4.f / 3.f, s.near_m, s.far_m);
    s.clipFromWorld = clipFromView * viewFromWorld;
    s.depth.assign(std::size_t{s.depthWidth} * s.depthHeight, 1.f);
    const float wall = windowDepthAt(6.f, s.near_m, s.far_m);
    for (std::uint32_t y = 0; y < s.depthHeight; ++y)
        for (std::uint32_t x = 2 * s.depthWidth / 3; x < s.depthWidth; ++x)
            s.depth[y * s.depthWidth + x] = wall;
    return s;
}

}  // namespace meadow::runtime::testing
