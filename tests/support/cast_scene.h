#pragma once
// Test support, header-only: depth images ray-cast from a few planes (a floor, walls) and
// upright strips facing the camera (a leaf seen flat), for the plant finding tests.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "meadow/capture/intrinsics.h"

namespace meadow::test {

struct Plane {
    float nx, ny, nz, d;  // n.p + d = 0, camera space, metres
};

// An upright rectangle facing the camera at depth z (metres, camera space; y runs down).
struct Strip {
    float x0, x1, y0, y1, z;
};

inline constexpr float kMaxCastRange_m = 4.f;

// Millimetres per pixel: the nearest plane or strip along the pixel's ray, 0 beyond
// kMaxCastRange_m.
inline cv::Mat1w castScene(const capture::Intrinsics& k, const std::vector<Plane>& planes,
                           const std::vector<Strip>& strips) {
    cv::Mat1w depth = cv::Mat1w::zeros(k.height_px, k.width_px);
    for (int y = 0; y < k.height_px; ++y)
        for (int x = 0; x < k.width_px; ++x) {
            // The ray through the pixel, scaled so that its z is 1: its t is the depth.
            const float dx = (static_cast<float>(x) - k.cx_px) / k.fx_px;
            const float dy = (static_cast<float>(y) - k.cy_px) / k.fy_px;
            float nearest = std::numeric_limits<float>::max();
            for (const Plane& p : planes) {
                const float along = p.nx * dx + p.ny * dy + p.nz;
                if (std::abs(along) < 1e-6f) continue;
                const float t = -p.d / along;
                if (t > 0.f) nearest = std::min(nearest, t);
            }
            for (const Strip& strip : strips) {
                const float t = strip.z, px = dx * t, py = dy * t;
                if (px >= strip.x0 && px <= strip.x1 && py >= strip.y0 && py <= strip.y1)
                    nearest = std::min(nearest, t);
            }
            if (nearest <= kMaxCastRange_m)
                depth(y, x) = static_cast<std::uint16_t>(nearest * 1000);
        }
    return depth;
}

inline cv::Mat1w castScene(const capture::Intrinsics& k, const std::vector<Plane>& planes,
                           const std::optional<Strip>& strip) {
    return castScene(k, planes, strip ? std::vector<Strip>{*strip} : std::vector<Strip>{});
}

}  // namespace meadow::test
