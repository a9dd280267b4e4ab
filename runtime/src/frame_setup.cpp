#include "frame_setup.h"

#include <cmath>
#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace meadow::runtime {
namespace {

glm::vec3 linearOf(glm::vec3 display) {
    return glm::pow(glm::clamp(display, 0.f, 1.f), glm::vec3(2.2f));
}

}  // namespace

glm::mat4 viewFromWorldOf(const CameraPose& pose) {
    const glm::vec3 forward = glm::normalize(pose.target_m - pose.position_m);
    // World +Y is up unless the camera looks straight up or down.
    const glm::vec3 up =
        std::abs(forward.y) > 0.999f ? glm::vec3(0.f, 0.f, -1.f) : glm::vec3(0.f, 1.f, 0.f);
    return glm::lookAt(pose.position_m, pose.target_m, up);
}

glm::mat4 lightClipFromWorldOf(const CameraPose& pose, const LightDescription& light,
                               const ShadowDescription& shadows, int cascade) {
    const glm::vec3 forward = glm::normalize(pose.target_m - pose.position_m);
    const float radius = 0.5f * shadows.distance_m *
                         (cascade == 0 ? 1.f : static_cast<float>(SHADOW_FAR_CASCADE_SCALE));
    const glm::vec3 centre = pose.position_m + forward * radius;
    const glm::vec3 toLight = glm::normalize(light.direction);
    const glm::vec3 up =
        std::abs(toLight.y) > 0.999f ? glm::vec3(0.f, 0.f, -1.f) : glm::vec3(0.f, 1.f, 0.f);
    const glm::mat4 lightView = glm::lookAt(glm::vec3(0.f), -toLight, up);
    glm::vec3 c = glm::vec3(lightView * glm::vec4(centre, 1.f));
    const float texel = 2.f * radius / static_cast<float>(shadows.mapSize_px);
    c.x = std::floor(c.x / texel) * texel;
    c.y = std::floor(c.y / texel) * texel;
    // Depth reaches four radii toward the light (tall props, hills) and one past the centre.
    const glm::mat4 projection = glm::ortho(c.x - radius, c.x + radius, c.y - radius, c.y + radius,
                                            -c.z - 4.f * radius, -c.z + radius);
    return projection * lightView;
}

gpu::FrameGpu frameGpuOf(const SceneDescription& scene, const CameraPose& pose, float time_s,
                         int width_px, int height_px) {
    const float aspect = static_cast<float>(width_px) / static_cast<float>(height_px);
    const glm::mat4 clipFromView =
        glm::perspective(glm::radians(scene.camera.verticalFov_deg), aspect, scene.camera.near_m,
                         scene.camera.far_m);
    gpu::FrameGpu frame{};
    frame.viewFromWorld = viewFromWorldOf(pose);
    frame.clipFromWorld = clipFromView * frame.viewFromWorld;
    frame.cameraPosition_time = glm::vec4(pose.position_m, time_s);
    frame.lightDirection = glm::vec4(scene.light.direction, scene.light.intensity);
    frame.viewport_px = glm::vec4(width_px, height_px, scene.camera.near_m, scene.camera.far_m);
    frame.wind = glm::vec4(scene.wind.direction, scene.wind.waveAmplitude_m_s);
    frame.worldFromClip = glm::inverse(frame.clipFromWorld);
    const LightDescription& light = scene.light;
    frame.horizon = glm::vec4(linearOf(light.skyColor), light.fogDistance_m);
    frame.zenith = glm::vec4(linearOf(light.zenithColor.value_or(light.skyColor)),
                             scene.shadows.enabled ? scene.shadows.strength : 0.f);
    if (scene.shadows.enabled)
        for (int c = 0; c < SHADOW_CASCADES; ++c)
            frame.lightClipFromWorld[c] = lightClipFromWorldOf(pose, light, scene.shadows, c);
    return frame;
}

float pixelSizePerMetre(const SceneDescription& scene, int height_px) {
    return 2.f * std::tan(glm::radians(scene.camera.verticalFov_deg) * 0.5f) /
           static_cast<float>(height_px);
}

}  // namespace meadow::runtime
