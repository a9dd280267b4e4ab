#include "sensor_noise_multipath.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace meadow::synth::detail {
namespace {

// One source per block of kSourceBlock_px^2 pixels, receivers every kReceiverStride_px: the
// bounce integrates over metres of surface, so its bias varies over centimetres, not pixels.
constexpr int kSourceBlock_px = 8;
constexpr int kReceiverStride_px = 4;
// The direct light at a grazing receiver tends to 0 and the ratio to infinity; beyond this the
// reading is dropped anyway (maxIncidence_deg), so the ratio is held there.
constexpr float kMinCosIncidence = 0.1f;  // ~84 deg
// Grid points interpolated into a pixel must lie on its surface: within 3 % of its depth (the
// edge jump, sensor_noise_edges.h) and with normals within ~25 deg.
constexpr float kSameSurfaceRelative = 0.03f;
constexpr float kSameSurfaceCos = 0.9f;

cv::Vec3f pointAt(const Intrinsics& k, int x, int y, float z_m) {
    return {(static_cast<float>(x) - k.cx_px) * z_m / k.fx_px,
            (static_cast<float>(y) - k.cy_px) * z_m / k.fy_px, z_m};
}

}  // namespace

float multipathLengthening_m(const cv::Vec3f& xP_m, const cv::Vec3f& nP,
                             const std::vector<MultipathSource>& sources, float albedo) {
    const float distanceP_m = static_cast<float>(cv::norm(xP_m));
    const float cosIncidence = std::max(std::abs(nP.dot(xP_m)) / distanceP_m, kMinCosIncidence);
    double weights = 0.0;
    double weightedPath_m = 0.0;
    for (const MultipathSource& q : sources) {
        const cv::Vec3f d = xP_m - q.x_m;  // from Q to P
        const float r_m = std::max(static_cast<float>(cv::norm(d)), q.footprint_m);
        if (!(r_m > 0.f)) continue;
        const float cosQ = q.n.dot(d) / r_m;
        const float cosP = -nP.dot(d) / r_m;
        if (cosQ <= 0.f || cosP <= 0.f) continue;
        const double w = albedo / std::numbers::pi * q.solidAngle_sr * cosQ * cosP * distanceP_m *
                         distanceP_m / (r_m * r_m * cosIncidence);
        const double extraPath_m = static_cast<double>(cv::norm(q.x_m)) + cv::norm(d) - distanceP_m;
        weights += w;
        weightedPath_m += w * extraPath_m;
    }
    const double radial_m = weightedPath_m / (2.0 * (1.0 + weights));
    return static_cast<float>(radial_m * xP_m[2] / distanceP_m);
}

cv::Mat1f multipathBias_m(const cv::Mat1f& depth_m, const cv::Mat3f& normals, const Intrinsics& k,
                          float albedo) {
    const int w = depth_m.cols;
    const int h = depth_m.rows;
    cv::Mat1f bias = cv::Mat1f::zeros(h, w);
    if (!(albedo > 0.f)) return bias;

    std::vector<MultipathSource> sources;
    const float blockSolidAngle_sr =
        static_cast<float>(kSourceBlock_px * kSourceBlock_px) / (k.fx_px * k.fy_px);
    for (int y = kSourceBlock_px / 2; y < h; y += kSourceBlock_px)
        for (int x = kSourceBlock_px / 2; x < w; x += kSourceBlock_px) {
            const float z_m = depth_m(y, x);
            if (z_m <= 0.f) continue;
            const cv::Vec3f p = pointAt(k, x, y, z_m);
            const float cosAxis = z_m / static_cast<float>(cv::norm(p));
            sources.push_back({p, normals(y, x), blockSolidAngle_sr * cosAxis * cosAxis * cosAxis,
                               static_cast<float>(kSourceBlock_px) * z_m / k.fx_px});
        }

    const auto exactAt = [&](int x, int y) {
        return multipathLengthening_m(pointAt(k, x, y, depth_m(y, x)), normals(y, x), sources,
                                      albedo);
    };
    const int gw = (w - 1) / kReceiverStride_px + 2;
    const int gh = (h - 1) / kReceiverStride_px + 2;
    const auto gridPixel = [&](int g, int size) {
        return std::min(g * kReceiverStride_px, size - 1);
    };
    cv::Mat1f grid = cv::Mat1f::zeros(gh, gw);
    for (int gy = 0; gy < gh; ++gy)
        for (int gx = 0; gx < gw; ++gx) {
            const int x = gridPixel(gx, w);
            const int y = gridPixel(gy, h);
            if (depth_m(y, x) > 0.f) grid(gy, gx) = exactAt(x, y);
        }

    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float z_m = depth_m(y, x);
            if (z_m <= 0.f) continue;
            const int gx = x / kReceiverStride_px;
            const int gy = y / kReceiverStride_px;
            const float fx = static_cast<float>(x - gx * kReceiverStride_px) / kReceiverStride_px;
            const float fy = static_cast<float>(y - gy * kReceiverStride_px) / kReceiverStride_px;
            float sum = 0.f, weight = 0.f;
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < 2; ++i) {
                    const int px = gridPixel(gx + i, w);
                    const int py = gridPixel(gy + j, h);
                    const float zg_m = depth_m(py, px);
                    if (zg_m <= 0.f || std::abs(zg_m - z_m) > kSameSurfaceRelative * z_m ||
                        normals(py, px).dot(normals(y, x)) < kSameSurfaceCos)
                        continue;
                    const float wgt = (i ? fx : 1.f - fx) * (j ? fy : 1.f - fy);
                    sum += wgt * grid(gy + j, gx + i);
                    weight += wgt;
                }
            bias(y, x) = weight > 1e-3f ? sum / weight : exactAt(x, y);
        }
    return bias;
}

}  // namespace meadow::synth::detail
