#include "sensor_noise_edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>

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

void applyLateralNoise(EdgeState& state, float sigma_px, std::uint64_t seed) {
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
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!band(y, x)) continue;
            PixelRng rng(seed, NoiseStream::Lateral, pixelIndex(x, y, w));
            // Clamped in long before narrowing, so no sigma can overflow the pixel arithmetic.
            const long dx = std::lround(sigma_px * rng.normal());
            const long dy = std::lround(sigma_px * rng.normal());
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

}  // namespace meadow::synth::detail
