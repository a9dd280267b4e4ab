#include "culling_reference.h"

#include <glm/glm.hpp>
#include <stdexcept>
#include <string>

#include "shared/physics_params.h"

namespace meadow::runtime {

// The shared GLSL, compiled as C++ (see physics_reference.cpp).
namespace cull_shader {
using namespace glm;
using gpu::BladeGpu;
using gpu::BladeRestGpu;
using gpu::CullParamsGpu;
using gpu::PhysicsParamsGpu;
#include "common_physics.glsl"
// common_culling.glsl uses common_physics.glsl: keep this order (separate include blocks).
#include "common_culling.glsl"
}  // namespace cull_shader

gpu::CullParamsGpu packCullParams(const CullSettings& s, const glm::mat4& clipFromWorld,
                                  glm::vec3 cameraPosition_m, float near_m, float far_m,
                                  std::uint32_t patchCount, std::uint32_t depthWidth,
                                  std::uint32_t depthHeight) {
    gpu::CullParamsGpu p{};
    p.clipFromWorld = clipFromWorld;
    p.cameraPosition_m = glm::vec4(cameraPosition_m, 1.f);
    p.orientationFrustum = glm::vec4(s.orientationThreshold, s.frustumTolerance, 0.f, 0.f);
    p.distanceLevels = glm::vec4(s.maxDistance_m, static_cast<float>(s.distanceLevels), 0.f, 0.f);
    p.depthRange_m = glm::vec4(near_m, far_m, s.occlusionBias_m, 0.f);
    const bool occlusion = s.occlusion && depthWidth > 0 && depthHeight > 0;
    const unsigned mask =
        (s.orientation ? CULL_TEST_ORIENTATION : 0u) | (s.frustum ? CULL_TEST_FRUSTUM : 0u) |
        (s.distance ? CULL_TEST_DISTANCE : 0u) | (occlusion ? CULL_TEST_OCCLUSION : 0u);
    p.counts = glm::uvec4(patchCount, mask, depthWidth, depthHeight);
    return p;
}

CullResult cullReference(std::span<const gpu::BladeGpu> blades,
                         std::span<const gpu::PatchGpu> patches, const gpu::CullParamsGpu& params,
                         const DepthImageView* depth) {
    using namespace cull_shader;
    const bool occlusionOn = (params.counts.y & CULL_TEST_OCCLUSION) != 0u;
    if (occlusionOn &&
        (!depth || depth->width != params.counts.z || depth->height != params.counts.w ||
         depth->depth.size() < std::size_t{depth->width} * depth->height))
        throw std::invalid_argument(
            "cullReference: occlusion is on but the depth image does not "
            "match params.counts.zw");
    if (patches.size() < params.counts.x)
        throw std::invalid_argument("cullReference: " + std::to_string(patches.size()) +
                                    " patches, params.counts.x asks for " +
                                    std::to_string(params.counts.x));
    const auto occluded = [&](vec4 q) {
        if (!clipPointInViewport(q)) return false;
        const ivec2 t = depthTexel(q, uvec2(params.counts.z, params.counts.w));
        const float sceneDepth = depth->depth[std::size_t(t.y) * depth->width + std::size_t(t.x)];
        return pointOccluded(q, sceneDepth, params.depthRange_m.x, params.depthRange_m.y,
                             params.depthRange_m.z);
    };

    CullResult result;
    // Mirrors main() of shaders/cull.comp, one patch (workgroup) after the other.
    for (std::uint32_t p = 0; p < params.counts.x; ++p) {
        const gpu::PatchGpu& patch = patches[p];
        const std::uint32_t first = patch.range.x, count = patch.range.y;
        if (std::size_t{first} + count > blades.size())
            throw std::invalid_argument("cullReference: patch " + std::to_string(p) +
                                        " reaches blade " + std::to_string(first + count) + " of " +
                                        std::to_string(blades.size()));
        const bool patchCulled =
            (params.counts.y & CULL_TEST_FRUSTUM) != 0u &&
            patchOutsideFrustum(params.clipFromWorld, vec3(patch.boundsMin_m),
                                vec3(patch.boundsMax_m), params.orientationFrustum.y);
        if (patchCulled) {
            result.stats.culledFrustum += count;
            continue;
        }
        for (std::uint32_t id = 0; id < count; ++id) {
            const BladeGpu& blade = blades[first + id];
            uint culledBy = cullBladeGeometric(blade, id, params);
            if (culledBy == 0u && occlusionOn) {
                const vec3 v0 = vec3(blade.v0_height);
                const vec3 v2 = vec3(blade.v2_stiffness);
                const vec3 m = bezierMidpoint(v0, vec3(blade.v1_width), v2);
                if (occluded(params.clipFromWorld * vec4(v0, 1.0f)) &&
                    occluded(params.clipFromWorld * vec4(m, 1.0f)) &&
                    occluded(params.clipFromWorld * vec4(v2, 1.0f)))
                    culledBy = CULL_TEST_OCCLUSION;
            }
            switch (culledBy) {
                case 0u:
                    result.visible.push_back(first + id);
                    break;
                case CULL_TEST_ORIENTATION:
                    ++result.stats.culledOrientation;
                    break;
                case CULL_TEST_FRUSTUM:
                    ++result.stats.culledFrustum;
                    break;
                case CULL_TEST_DISTANCE:
                    ++result.stats.culledDistance;
                    break;
                default:
                    ++result.stats.culledOcclusion;
                    break;
            }
        }
    }
    return result;
}

}  // namespace meadow::runtime
