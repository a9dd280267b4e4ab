#include "far_field.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <opencv2/imgproc.hpp>

#include "seeding.h"

namespace meadow::runtime {
namespace {

// blade.frag's per-blade hue variation, from the same lowbias32 hash.
float variation(std::uint32_t i) {
    i ^= i >> 16;
    i *= 0x7feb352du;
    i ^= i >> 15;
    i *= 0x846ca68bu;
    i ^= i >> 16;
    return static_cast<float>(i & 0xffffu) / 65535.f;
}

cv::Scalar encoded(glm::vec3 linear, double alpha) {
    const auto e = [](float c) { return 255.0 * std::pow(std::clamp(c, 0.f, 1.f), 1.0 / 2.2); };
    return {e(linear.r), e(linear.g), e(linear.b), alpha};
}

}  // namespace

FarFieldSlices buildFarFieldSlices(const std::vector<gpu::TileInstanceGpu>& patch,
                                   const SceneDescription& scene, int perAxis, int width_px,
                                   int height_px) {
    FarFieldSlices s;
    s.perAxis = perAxis;
    s.tileSize_m = scene.tiling->tileSize_m;
    s.spacing_m = s.tileSize_m / static_cast<float>(perAxis);
    for (const gpu::TileInstanceGpu& g : patch)
        s.height_m = std::max({s.height_m, g.restV1_width.y, g.restV2_height.y});
    s.height_m = std::max(s.height_m, 1e-3f);
    for (int i = 0; i < 2 * perAxis; ++i)
        s.layers.emplace_back(height_px, width_px, CV_8UC4, cv::Scalar(0, 0, 0, 0));

    const glm::vec3 up(0.f, 1.f, 0.f);
    const float texelU = s.tileSize_m / static_cast<float>(width_px);
    const float texelV = s.height_m / static_cast<float>(height_px);
    const RenderSettings& r = scene.render;
    constexpr int kSegments = 8;
    for (std::size_t b = 0; b < patch.size(); ++b) {
        const gpu::TileInstanceGpu& g = patch[b];
        const float angle = g.place.w;
        const glm::vec3 w = bladeWidthDirection(up, angle);
        const glm::vec3 d = glm::cross(w, up);
        const glm::vec3 root(g.place.x, 0.f, g.place.z);
        const auto world = [&](glm::vec4 local) {
            return root + local.x * d + local.y * up + local.z * w;
        };
        const glm::vec3 v0 = root, v1 = world(g.restV1_width), v2 = world(g.restV2_height);
        const modeling::Archetype& arch = scene.archetypes[static_cast<std::size_t>(g.look.x)];
        const float widest = std::max(arch.width.maxWidth_m(), 1e-6f);
        const float hue = 0.8f + 0.4f * variation(static_cast<std::uint32_t>(b) * 0x9e3779b1u);
        for (int axis = 0; axis < 2; ++axis) {
            // axis 0: planes of constant z, u along x; axis 1: constant x, u along z.
            const float across = axis == 0 ? root.z : root.x;
            const int slab = std::clamp(static_cast<int>(across / s.spacing_m), 0, perAxis - 1);
            cv::Mat& layer = s.layers[static_cast<std::size_t>(axis * perAxis + slab)];
            const float projected = std::abs(axis == 0 ? w.x : w.z);
            for (int k = 0; k < kSegments; ++k) {
                cv::Point quad[4];
                glm::vec3 colour{};
                for (int e = 0; e < 2; ++e) {
                    const float t = static_cast<float>(k + e) / kSegments;
                    const glm::vec3 c = (1 - t) * (1 - t) * v0 + 2 * (1 - t) * t * v1 + t * t * v2;
                    const float halfWidth =
                        std::max(0.5f * g.restV1_width.w * arch.width.at(t) / widest * projected,
                                 0.5f * texelU);
                    const float u = (axis == 0 ? c.x : c.z) / texelU;
                    const float v = c.y / texelV;
                    quad[e == 0 ? 0 : 3] =
                        cv::Point(static_cast<int>(std::lround((u - halfWidth / texelU) * 16)),
                                  static_cast<int>(std::lround(v * 16)));
                    quad[e == 0 ? 1 : 2] =
                        cv::Point(static_cast<int>(std::lround((u + halfWidth / texelU) * 16)),
                                  static_cast<int>(std::lround(v * 16)));
                    if (e == 0)
                        colour = glm::mix(r.rootColor, r.tipColor, t + 0.5f / kSegments) * hue *
                                 glm::mix(r.aoAtRoot, 1.f, t + 0.5f / kSegments);
                }
                // Blades that lean past the tile's edge wrap round: the slices repeat with it.
                for (int shift : {-width_px, 0, width_px}) {
                    cv::Point moved[4];
                    for (int q = 0; q < 4; ++q) moved[q] = quad[q] + cv::Point(shift * 16, 0);
                    cv::fillConvexPoly(layer, moved, 4, encoded(colour, 255), cv::LINE_AA, 4);
                }
            }
        }
    }
    // As terrain.frag sees a far, filtered slice: the covered texels' encoded colour averaged
    // (an empty texel is black and clear, so colour sums over coverage), then made linear.
    constexpr int kBands = FarFieldSlices::kHeightBands;
    std::array<double, kBands> covered{};
    std::array<glm::dvec3, kBands> encoded{};
    for (const cv::Mat& layer : s.layers)
        for (int y = 0; y < layer.rows; ++y) {
            const int band = std::min(y * kBands / layer.rows, kBands - 1);
            for (int x = 0; x < layer.cols; ++x) {
                const cv::Vec4b t = layer.at<cv::Vec4b>(y, x);
                covered[band] += t[3] / 255.0;
                for (int c = 0; c < 3; ++c) encoded[band][c] += t[c] / 255.0;
            }
        }
    const double texelsPerBand =
        static_cast<double>(s.layers.size()) * width_px * height_px / kBands;
    for (int b = 0; b < kBands; ++b) {
        s.bandCoverage[b] = static_cast<float>(covered[b] / texelsPerBand);
        if (covered[b] > 0.0)
            for (int c = 0; c < 3; ++c)
                s.bandAlbedo[b][c] =
                    static_cast<float>(std::pow(std::min(encoded[b][c] / covered[b], 1.0), 2.2));
    }
    return s;
}

}  // namespace meadow::runtime
