#pragma once
// What every pass of a frame reads about it (FrameGpu): the camera's matrices, the light and its
// shadow map's projection, the sky and the haze, the wind; built the same way for the renderer
// and for tests that run single passes.
#include <glm/mat4x4.hpp>

#include "meadow/runtime/renderer.h"
#include "meadow/runtime/scene.h"
#include "shared/blade_types.h"

namespace meadow::runtime {

glm::mat4 viewFromWorldOf(const CameraPose& pose);

// A shadow cascade's projection: an orthographic box along the light over the part of the view
// within the shadow distance (the far cascade: SHADOW_FAR_CASCADE_SCALE times it), its centre
// snapped to whole shadow-map texels (in light space) so the shadows do not shimmer as the
// camera moves.
glm::mat4 lightClipFromWorldOf(const CameraPose& pose, const LightDescription& light,
                               const ShadowDescription& shadows, int cascade);

gpu::FrameGpu frameGpuOf(const SceneDescription& scene, const CameraPose& pose, float time_s,
                         int width_px, int height_px);

// World size of one pixel at 1 m (m/m): the image height spans 2 tan(fov / 2) at unit distance.
float pixelSizePerMetre(const SceneDescription& scene, int height_px);

}  // namespace meadow::runtime
