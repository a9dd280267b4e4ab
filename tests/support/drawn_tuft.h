#pragma once
// Test and benchmark support, header-only: a tuft drawn with OpenCV, blades as filled polygons
// around quadratic Bézier spines at known depths, standing on a ground plane seen from the side
// in front of a back wall. Needs nothing but OpenCV, so the segmentation tests do not wait for
// the simulated sensor. Labels: 0 = ground / wall, i = blade i (1-based).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "meadow/capture/depth_frame.h"

namespace meadow::capture::drawn {

struct Blade {
    cv::Point2f base_px, control_px, tip_px;  // quadratic Bézier spine
    float baseWidth_px = 8.f;
    float tipWidth_px = 1.f;
    float depth_m = 1.0f;
};

struct Scene {
    std::vector<Blade> blades;
    float cameraHeight_m = 0.3f;  // ground plane y = +cameraHeight_m (y down); 0 = no ground
    float wallDepth_m = 3.0f;     // 0 = no wall (no reading beyond the ground)
};

struct Noise {
    float sigma_mm = 0.f;         // Gaussian depth noise
    float dropoutRate = 0.f;      // share of pixels reading 0
    float flyingPixelRate = 0.f;  // share of blade-edge pixels reading a depth halfway back
    int lateralJitter_px = 0;     // edge jitter: the blade polygon's vertices move this much
    unsigned seed = 1;
};

struct Drawn {
    DepthFrame frame;
    cv::Mat1w labels;
    int bladeCount = 0;
};

inline cv::Point2f bezier(const Blade& b, float t) {
    const float u = 1.f - t;
    return u * u * b.base_px + 2.f * u * t * b.control_px + t * t * b.tip_px;
}

inline std::vector<cv::Point> bladePolygon(const Blade& b, cv::RNG& rng, int jitter_px) {
    constexpr int kSamples = 40;
    std::vector<cv::Point2f> left, right;
    for (int i = 0; i <= kSamples; ++i) {
        const float t = static_cast<float>(i) / kSamples;
        const cv::Point2f p = bezier(b, t);
        const cv::Point2f q =
            bezier(b, std::min(1.f, t + 1e-3f)) - bezier(b, std::max(0.f, t - 1e-3f));
        const cv::Point2f n =
            cv::Point2f(-q.y, q.x) * (1.f / std::max(1e-6f, std::hypot(q.x, q.y)));
        const float w = 0.5f * (b.baseWidth_px + (b.tipWidth_px - b.baseWidth_px) * t);
        left.push_back(p + w * n);
        right.push_back(p - w * n);
    }
    std::vector<cv::Point> poly;
    const auto j = [&] { return jitter_px > 0 ? rng.uniform(-jitter_px, jitter_px + 1) : 0; };
    for (const auto& p : left) poly.emplace_back(cvRound(p.x) + j(), cvRound(p.y) + j());
    for (auto it = right.rbegin(); it != right.rend(); ++it)
        poly.emplace_back(cvRound(it->x) + j(), cvRound(it->y) + j());
    return poly;
}

inline Drawn draw(const Scene& scene, const Noise& noise = {},
                  Intrinsics K = Intrinsics::kinectV1()) {
    Drawn out;
    out.frame.intrinsics = K;
    out.frame.depth_mm = cv::Mat1w(K.height_px, K.width_px, std::uint16_t{0});
    out.labels = cv::Mat1w(K.height_px, K.width_px, std::uint16_t{0});
    for (int v = 0; v < K.height_px; ++v) {
        const float ray_y = (static_cast<float>(v) - K.cy_px) / K.fy_px;
        float z = scene.wallDepth_m;
        if (scene.cameraHeight_m > 0.f && ray_y > 0.f) {
            const float ground = scene.cameraHeight_m / ray_y;
            if (z <= 0.f || ground < z) z = ground;
        }
        if (z > 0.f)
            out.frame.depth_mm.row(v).setTo(static_cast<std::uint16_t>(std::lround(z * 1000.f)));
    }
    cv::RNG rng(noise.seed);
    std::vector<int> order(scene.blades.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return scene.blades[static_cast<size_t>(a)].depth_m >
               scene.blades[static_cast<size_t>(b)].depth_m;
    });
    cv::Mat1b edge(out.labels.size(), std::uint8_t{0});
    for (int i : order) {
        const Blade& b = scene.blades[static_cast<size_t>(i)];
        const auto poly = bladePolygon(b, rng, noise.lateralJitter_px);
        const std::vector<std::vector<cv::Point>> polys{poly};
        cv::fillPoly(out.frame.depth_mm, polys, cv::Scalar(std::lround(b.depth_m * 1000.f)));
        cv::fillPoly(out.labels, polys, cv::Scalar(i + 1));
        cv::polylines(edge, polys, true, 255);
    }
    out.bladeCount = static_cast<int>(scene.blades.size());
    if (noise.sigma_mm > 0.f || noise.dropoutRate > 0.f || noise.flyingPixelRate > 0.f)
        for (int y = 0; y < out.labels.rows; ++y)
            for (int x = 0; x < out.labels.cols; ++x) {
                auto& d = out.frame.depth_mm(y, x);
                if (d == 0) continue;
                if (noise.dropoutRate > 0.f && rng.uniform(0.f, 1.f) < noise.dropoutRate) {
                    d = 0;
                    continue;
                }
                if (noise.flyingPixelRate > 0.f && edge(y, x) &&
                    rng.uniform(0.f, 1.f) < noise.flyingPixelRate) {
                    d = static_cast<std::uint16_t>(d + 400 + rng.uniform(0, 400));
                    continue;
                }
                if (noise.sigma_mm > 0.f)
                    d = static_cast<std::uint16_t>(
                        std::clamp(d + rng.gaussian(noise.sigma_mm), 1.0, 65535.0));
            }
    return out;
}

// A fan of n blades standing on the ground at depth ~1 m, tips spread over +-spread_deg.
inline Scene fan(int n, float spread_deg = 60.f, float length_px = 160.f, float baseWidth_px = 9.f,
                 float bend = 0.15f) {
    Scene s;
    const Intrinsics K = Intrinsics::kinectV1();
    const float depth_m = 1.0f;
    const float baseY = K.cy_px + K.fy_px * s.cameraHeight_m / depth_m - 2.f;  // on the ground
    for (int i = 0; i < n; ++i) {
        const float f =
            n == 1 ? 0.f : static_cast<float>(i) / static_cast<float>(n - 1) * 2.f - 1.f;
        const float a = f * spread_deg * std::numbers::pi_v<float> / 180.f;
        Blade b;
        b.base_px = {K.cx_px + f * baseWidth_px * 0.6f * static_cast<float>(n) * 0.5f, baseY};
        const float len = length_px * (0.85f + 0.15f * std::cos(3.f * static_cast<float>(i)));
        b.tip_px = b.base_px + cv::Point2f(std::sin(a), -std::cos(a)) * len;
        const cv::Point2f mid = 0.5f * (b.base_px + b.tip_px);
        b.control_px = mid + cv::Point2f(-std::cos(a), -std::sin(a)) * (bend * len * f) +
                       cv::Point2f(0.f, -0.1f * len);
        b.baseWidth_px = baseWidth_px;
        b.depth_m = depth_m + 0.01f * static_cast<float>(i % 3);
        s.blades.push_back(b);
    }
    return s;
}

}  // namespace meadow::capture::drawn
