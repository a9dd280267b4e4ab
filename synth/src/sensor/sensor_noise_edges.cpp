#include "sensor_noise_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

#include "sensor_noise_rng.h"

namespace meadow::synth::detail {
namespace {

// Only pixels this many standard deviations of lateral noise from an edge can be displaced
// onto another surface; farther ones would only move along a smooth surface.
constexpr float kLateralReachSigmas = 3.f;

struct Offset {
    int dx;
    int dy;
};
constexpr std::array<Offset, 4> kFourNeighbours{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};

std::uint64_t pixelIndex(int x, int y, int width) {
    return static_cast<std::uint64_t>(y) * static_cast<std::uint64_t>(width) +
           static_cast<std::uint64_t>(x);
}

}  // namespace

bool isDepthJump(float a_m, float b_m) {
    if ((a_m > 0.f) != (b_m > 0.f)) return true;
    if (a_m <= 0.f) return false;
    return std::abs(a_m - b_m) > kDepthJumpRelative * std::min(a_m, b_m);
}

cv::Mat1b depthDiscontinuities(const cv::Mat1f& surface_m) {
    cv::Mat1b edges = cv::Mat1b::zeros(surface_m.size());
    for (int y = 0; y < surface_m.rows; ++y)
        for (int x = 0; x < surface_m.cols; ++x) {
            // Right and down neighbours only: each pair is visited once and marks both sides.
            if (x + 1 < surface_m.cols && isDepthJump(surface_m(y, x), surface_m(y, x + 1)))
                edges(y, x) = edges(y, x + 1) = 255;
            if (y + 1 < surface_m.rows && isDepthJump(surface_m(y, x), surface_m(y + 1, x)))
                edges(y, x) = edges(y + 1, x) = 255;
        }
    return edges;
}

namespace {

// Unit-variance displacement fields (u, v) for correlated lateral noise: white noise per pixel
// (two draws of one counter stream) smoothed by a Gaussian of sigma correlation_px, divided by
// the standard deviation smoothing leaves, sum(g_i^2) for the separable kernel g.
std::pair<cv::Mat1f, cv::Mat1f> lateralField(int w, int h, float correlation_px,
                                             std::uint64_t seed) {
    cv::Mat1f u(h, w), v(h, w);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            PixelRng rng(seed, NoiseStream::LateralField, pixelIndex(x, y, w));
            u(y, x) = static_cast<float>(rng.normal());
            v(y, x) = static_cast<float>(rng.normal());
        }
    const int radius = static_cast<int>(std::ceil(3.f * correlation_px));
    const cv::Mat1d g = cv::getGaussianKernel(2 * radius + 1, correlation_px, CV_64F);
    double sumSquares = 0.0;
    for (int i = 0; i < g.rows; ++i) sumSquares += g(i) * g(i);
    const double gain = 1.0 / sumSquares;
    for (cv::Mat1f* field : {&u, &v}) {
        cv::sepFilter2D(*field, *field, CV_32F, g, g, {-1, -1}, 0.0, cv::BORDER_REFLECT);
        *field *= gain;
    }
    return {u, v};
}

}  // namespace

void applyLateralNoise(EdgeState& state, float sigma_px, float correlation_px, std::uint64_t seed) {
    if (!(sigma_px > 0.f)) return;
    // Beyond the image's size a wider band changes nothing.
    const float reachLimit_px =
        static_cast<float>(std::max(state.surface_m.cols, state.surface_m.rows));
    const int reach_px = std::max(
        1, static_cast<int>(std::ceil(std::min(kLateralReachSigmas * sigma_px, reachLimit_px))));
    cv::Mat1b band;
    // Edges of what is read as well as of what is there: the borders of projector shadows and
    // grazing dropouts are as ragged on a real sensor as silhouettes are.
    const cv::Mat1b edges =
        depthDiscontinuities(state.surface_m) | depthDiscontinuities(state.reading_m);
    cv::dilate(edges, band,
               cv::getStructuringElement(cv::MORPH_RECT, {2 * reach_px + 1, 2 * reach_px + 1}));
    // Read from copies: every pixel samples the undisplaced image, whatever the loop order.
    const EdgeState source{state.surface_m.clone(), state.reading_m.clone(),
                           state.incidence_rad.clone()};
    const int w = band.cols;
    const int h = band.rows;
    const bool correlated = correlation_px > 0.f;
    const auto [fieldU, fieldV] =
        correlated ? lateralField(w, h, correlation_px, seed) : std::pair<cv::Mat1f, cv::Mat1f>{};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!band(y, x)) continue;
            double u = 0.0, v = 0.0;
            if (correlated) {
                u = fieldU(y, x);
                v = fieldV(y, x);
            } else {
                PixelRng rng(seed, NoiseStream::Lateral, pixelIndex(x, y, w));
                u = rng.normal();
                v = rng.normal();
            }
            // Clamped in long before narrowing, so no sigma can overflow the pixel arithmetic.
            const long dx = std::lround(sigma_px * u);
            const long dy = std::lround(sigma_px * v);
            const auto sx = static_cast<int>(std::clamp<long>(x + dx, 0, w - 1));
            const auto sy = static_cast<int>(std::clamp<long>(y + dy, 0, h - 1));
            state.surface_m(y, x) = source.surface_m(sy, sx);
            state.reading_m(y, x) = source.reading_m(sy, sx);
            state.incidence_rad(y, x) = source.incidence_rad(sy, sx);
        }
}

int applyFlyingPixels(EdgeState& state, float rate, std::uint64_t seed) {
    if (!(rate > 0.f)) return 0;
    const cv::Mat1f& surface = state.surface_m;
    const int w = surface.cols;
    const int h = surface.rows;
    cv::Mat1f flown = state.reading_m.clone();  // neighbours are read before any pixel flies
    int count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float own_m = state.reading_m(y, x);
            if (own_m <= 0.f) continue;
            float other_m = 0.f;
            float largestJump_m = 0.f;
            for (const Offset& d : kFourNeighbours) {
                const int nx = x + d.dx;
                const int ny = y + d.dy;
                if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                const float neighbour_m = surface(ny, nx);
                if (neighbour_m <= 0.f || !isDepthJump(surface(y, x), neighbour_m)) continue;
                const float jump_m = std::abs(neighbour_m - own_m);
                if (jump_m > largestJump_m) {
                    largestJump_m = jump_m;
                    other_m = neighbour_m;
                }
            }
            if (other_m <= 0.f) continue;
            PixelRng rng(seed, NoiseStream::FlyingPixel, pixelIndex(x, y, w));
            if (rng.uniform() >= rate) continue;
            const auto t = static_cast<float>(rng.uniform());
            flown(y, x) = own_m + t * (other_m - own_m);
            ++count;
        }
    state.reading_m = flown;
    return count;
}

int applyEdgeFattening(EdgeState& state, float width_px) {
    if (!(width_px > 0.f)) return 0;
    const int radius = static_cast<int>(std::floor(width_px));
    std::vector<Offset> disc;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx)
            if ((dx != 0 || dy != 0) &&
                static_cast<float>(dx * dx + dy * dy) <= width_px * width_px)
                disc.push_back({dx, dy});
    const cv::Mat1f reading = state.reading_m.clone();  // every pixel sees the unfattened image
    const cv::Mat1f incidence = state.incidence_rad.clone();
    const int w = reading.cols;
    const int h = reading.rows;
    int count = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float own_m = reading(y, x);
            float nearest_m = 0.f;
            cv::Point from;
            for (const Offset& d : disc) {
                const int nx = x + d.dx;
                const int ny = y + d.dy;
                if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                const float other_m = reading(ny, nx);
                if (other_m <= 0.f ||
                    (own_m > 0.f && !(other_m < own_m && isDepthJump(own_m, other_m))))
                    continue;
                if (nearest_m == 0.f || other_m < nearest_m) {
                    nearest_m = other_m;
                    from = {nx, ny};
                }
            }
            if (nearest_m == 0.f) continue;
            state.reading_m(y, x) = nearest_m;
            state.incidence_rad(y, x) = incidence(from);
            ++count;
        }
    return count;
}

}  // namespace meadow::synth::detail
