#include "sensor_noise_shadow.h"

#include <algorithm>
#include <cmath>

#include "rasteriser.h"

namespace meadow::synth::detail {
namespace {

// A camera pixel is shadowed only when the projector sees something clearly in front of it:
// the projector's depth is sampled at the nearest of its pixel centres, up to 0.5 px from the
// exact spot, where a surface at incidence theta differs by 0.5 z/fx tan(theta) (~5 mm at 1 m
// and 80 deg); so the occluder must be nearer by 5 mm plus 1 % of the depth.
constexpr float kShadowToleranceAbsolute_m = 0.005f;
constexpr float kShadowToleranceRelative = 0.01f;
// Nearest depth for which the projector's image is widened to cover the camera's: closer
// surfaces would need a huge margin, and the sensor reads nothing that close anyway.
constexpr float kShadowNearestCovered_m = 0.2f;

}  // namespace

cv::Mat1b projectorShadow(const std::vector<LabelledMesh>& meshes, const Intrinsics& camera,
                          const cv::Mat1f& exact_m, float baseline_m, float nearestDepth_m) {
    // The projector shares the camera's orientation, focal length and rows; a point at depth z
    // lands fx b / z px further left in its image, so its image is widened on the left.
    const float coveredDepth_m = std::max(nearestDepth_m, kShadowNearestCovered_m);
    const int margin_px =
        static_cast<int>(std::ceil(camera.fx_px * baseline_m / coveredDepth_m)) + 1;
    Intrinsics projector = camera;
    projector.width_px += margin_px;
    projector.cx_px += static_cast<float>(margin_px);
    const cv::Mat1f lit_m =
        rasterise(meshes, projector, {baseline_m, 0.f, 0.f}, /*withAttributes=*/false).depth_m;

    cv::Mat1b shadow = cv::Mat1b::zeros(exact_m.size());
    for (int y = 0; y < exact_m.rows; ++y)
        for (int x = 0; x < exact_m.cols; ++x) {
            const float z_m = exact_m(y, x);
            if (z_m <= 0.f) continue;
            // Same point in the projector's frame: x shifts by -b, y and z are unchanged, so it
            // stays on row y (the epipolar line) at column x - fx b / z in camera pixels.
            const float u_px = static_cast<float>(x) - camera.fx_px * baseline_m / z_m +
                               static_cast<float>(margin_px);
            const long column = std::lround(u_px);
            if (column < 0 || column >= projector.width_px) continue;  // outside: call it lit
            const float occluder_m = lit_m(y, static_cast<int>(column));
            if (occluder_m > 0.f &&
                occluder_m < z_m - kShadowToleranceAbsolute_m - kShadowToleranceRelative * z_m)
                shadow(y, x) = 255;
        }
    return shadow;
}

}  // namespace meadow::synth::detail
