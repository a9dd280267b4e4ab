// Continuing a segmented blade past its visible tip (blade_tip.h).
#include "meadow/modeling/blade_tip.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <vector>

#include "chain_resample.h"

namespace meadow::modeling {
namespace {

// Fewest points in either least-squares window, and fewest skeleton points to extend.
constexpr int kMinWindowPoints = 3;
constexpr int kMinSkeletonPoints = 8;
// The blade's width in pixels, for recurringTrailExtension: this quantile of its widths.
constexpr float kWidestQuantile = 0.9f;

struct Line {
    float intercept = 0.f, slope = 0.f, slopeStdError = 0.f;
};

// Least-squares y = intercept + slope x over the samples with from <= x <= to.
Line fitLine(const std::vector<float>& x, const std::vector<float>& y, float from, float to) {
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (x[i] < from || x[i] > to) continue;
        n += 1, sx += x[i], sy += y[i], sxx += double(x[i]) * x[i], sxy += double(x[i]) * y[i];
    }
    Line line;
    const double det = n * sxx - sx * sx;
    if (n < kMinWindowPoints || !(det > 0.0)) return {0.f, 0.f, 1e30f};
    line.slope = static_cast<float>((n * sxy - sx * sy) / det);
    line.intercept = static_cast<float>((sy - line.slope * sx) / n);
    double residual = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        if (x[i] < from || x[i] > to) continue;
        const double r = y[i] - (line.intercept + line.slope * x[i]);
        residual += r * r;
    }
    const double variance = n > 2 ? residual / (n - 2) : 0.0;
    line.slopeStdError = static_cast<float>(std::sqrt(variance * n / det));
    return line;
}

}  // namespace

void extendSkeletonTip(Skeleton& s, const TipParams& params) {
    const int n = static_cast<int>(s.points_m.size());
    if (s.width_m.size() != s.points_m.size())
        throw std::invalid_argument("extendSkeletonTip: need a lifted skeleton with widths");
    s.tipExtension_m = 0.f;
    s.tipPoints = 0;
    if (n < kMinSkeletonPoints) return;

    // Arc length from the base along the 3D chain.
    std::vector<float> arc_m(static_cast<std::size_t>(n), 0.f);
    for (int i = 1; i < n; ++i)
        arc_m[i] = arc_m[i - 1] + glm::distance(s.points_m[i - 1], s.points_m[i]);
    const float length_m = arc_m.back();
    if (!(length_m > 0.f)) return;

    // Width trend over the tapering part, extrapolated to zero.
    const float widthTo_m = params.widthFitTo * length_m;
    const Line w = fitLine(arc_m, s.width_m, params.widthFitFrom * length_m, widthTo_m);
    const bool tapers = w.slope < 0.f && -w.slope >= params.minSlopeSignificance * w.slopeStdError;
    float extension_m = params.fixedExtensionFraction * length_m;
    if (!(params.fixedExtensionFraction > 0.f)) {
        if (!tapers) return;
        extension_m =
            std::min(-w.intercept / w.slope - length_m, params.maxExtensionFraction * length_m);
    }
    if (!(extension_m > 0.f)) return;

    // End tangent: least-squares line through the last points against arc length.
    glm::vec3 direction{0.f};
    {
        const float from_m = params.tangentFitFrom * length_m;
        std::vector<float> coordinate(static_cast<std::size_t>(n));
        for (int axis = 0; axis < 3; ++axis) {
            for (int i = 0; i < n; ++i) coordinate[i] = s.points_m[i][axis];
            direction[axis] = fitLine(arc_m, coordinate, from_m, length_m).slope;
        }
    }
    if (!(glm::length(direction) > 0.f)) return;
    direction = glm::normalize(direction);

    // Widths past the trend's window are the contour's closing, not the blade: they follow the
    // trend (pixels scaled by the last in-window point's pixels per metre), down to 0 at the new
    // tip.
    const auto trend = [&](float a_m) { return std::max(0.f, w.intercept + w.slope * a_m); };
    std::vector<float> width_m = s.width_m, width_px = s.width_px;
    const bool hasPx = width_px.size() == s.points_m.size();
    float pxPerMetre = 0.f;
    for (int i = 0; i < n; ++i) {
        if (arc_m[i] <= widthTo_m || !tapers) {
            if (hasPx && width_m[i] > 0.f) pxPerMetre = width_px[i] / width_m[i];
            continue;
        }
        width_m[i] = trend(arc_m[i]);
        if (hasPx) width_px[i] = width_m[i] * pxPerMetre;
    }

    std::vector<glm::vec3> points = s.points_m;
    points.push_back(s.points_m.back() + extension_m * direction);
    width_m.push_back(0.f);
    if (hasPx) width_px.push_back(0.f);
    // The midline continues along its own end direction, scaled to the 3D extension.
    std::vector<glm::vec2> midline = s.midline_px, across = s.across_px;
    if (midline.size() == s.points_m.size()) {
        const int k = std::max(1, static_cast<int>(std::lround((1.f - params.tangentFitFrom) *
                                                               static_cast<float>(n - 1))));
        const float chord_m = arc_m[n - 1] - arc_m[n - 1 - k];
        const glm::vec2 step = midline[n - 1] - midline[n - 1 - k];
        midline.push_back(midline.back() + (chord_m > 0.f ? extension_m / chord_m : 0.f) * step);
    }
    if (across.size() == s.points_m.size()) across.push_back(across.back());
    std::vector<float> depth = s.depth_m;
    if (depth.size() == s.points_m.size()) depth.push_back(points.back().z);
    std::vector<glm::vec3> acrossStep = s.acrossStep_m;
    if (acrossStep.size() == s.points_m.size()) acrossStep.push_back(glm::vec3(0.f));

    const auto stations = detail::arcLengthStations(points, n);
    s.tipPoints =
        static_cast<int>(std::count_if(stations.begin(), stations.end(), [n](const auto& st) {
            return st.first == static_cast<std::size_t>(n - 1);
        }));
    s.points_m = detail::sampleAt(points, stations);
    s.points_m.back() = points.back();
    s.width_m = detail::sampleAt(width_m, stations);
    s.width_m.back() = 0.f;
    if (width_px.size() == points.size()) {
        s.width_px = detail::sampleAt(width_px, stations);
        s.width_px.back() = 0.f;
    }
    if (midline.size() == points.size()) s.midline_px = detail::sampleAt(midline, stations);
    if (across.size() == points.size()) {
        s.across_px = detail::sampleAt(across, stations);
        for (glm::vec2& a : s.across_px)
            if (glm::length(a) > 0.f) a = glm::normalize(a);
    }
    if (depth.size() == points.size()) s.depth_m = detail::sampleAt(depth, stations);
    if (acrossStep.size() == points.size()) s.acrossStep_m = detail::sampleAt(acrossStep, stations);
    s.tipExtension_m = extension_m;
    s.arcFraction.assign(static_cast<std::size_t>(n), 0.f);
    for (int i = 1; i < n; ++i)
        s.arcFraction[i] = s.arcFraction[i - 1] + glm::distance(s.points_m[i - 1], s.points_m[i]);
    const float total = s.arcFraction.back();
    for (float& f : s.arcFraction) f = total > 0.f ? f / total : 0.f;
}

std::optional<float> recurringTrailExtension(const Skeleton& s, const TipParams& params) {
    std::vector<float> width_px = s.width_px;
    if (width_px.empty()) return std::nullopt;
    const auto widest =
        width_px.begin() +
        static_cast<std::ptrdiff_t>(kWidestQuantile * static_cast<float>(width_px.size() - 1));
    std::nth_element(width_px.begin(), widest, width_px.end());
    if (!(*widest > 0.f)) return std::nullopt;
    return std::min(params.maxExtensionFraction, params.extensionOnRecurringTrail_px / *widest);
}

}  // namespace meadow::modeling
