// Symmetric contour matching and back-projection (Fan & Sheng 2017, Sec. 4.3).
#include "meadow/modeling/skeleton.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "meadow/modeling/error.h"

namespace meadow::modeling {
namespace {

// cv::findContours returns the centres of the boundary pixels, half a pixel inside the true
// silhouette on every side: a blade w pixels wide has boundary centres w - 1 pixels apart. This
// adds the missing pixel back to every matched width, and half a pixel to each end of the chain.
constexpr float kBoundaryFootprint_px = 1.f;
constexpr float kHalfPixel_px = 0.5f;
// Fraction of the chain used to estimate the end tangents for the half-pixel extension: adjacent
// points of a 128-point chain are closer than a pixel, so their difference is pure rounding.
constexpr float kEndTangentFraction = 0.08f;
// Half window (contour points) of the moving average applied to each contour side before
// resampling. The 8-connected chain of boundary pixels is a staircase whose length overstates
// the true edge by up to 8 % depending on its orientation; where a side turns, that distortion
// varies along it, arc-length pairing drifts and widths come out too large. Averaging a few
// points puts the chain back on the edge line.
constexpr int kSideSmoothingHalfWindow = 3;
// Half window, as a fraction of the chain, of the central difference giving the midline's tangent.
constexpr float kTangentHalfWindowFraction = 0.03f;
// Running-median half window (points) for the flying-pixel test in the chain's middle.
constexpr int kDepthMedianHalfWindow = 6;
// Middle part of the chain whose readings are tested against a centred running median; outside
// it, readings are tested against the extrapolation of the accepted ones (see rejectAndFill).
// The middle half: blade bases and thin tips are where flying pixels and hole edges gather.
constexpr float kReliableMiddleFraction = 0.5f;
// Accepted readings (fraction of the chain, at least kMinExtrapolationPoints) through which the
// line is fitted that a reading further out must agree with, and that fills the chain's ends.
constexpr float kEndExtrapolationFraction = 0.12f;
constexpr int kMinExtrapolationPoints = 4;
// Half window (as a fraction of the chain) of the local linear regression that smooths depth
// along the chain; at the ends it extrapolates from the interior, where readings are reliable.
constexpr float kDepthRegressionFraction = 0.06f;
// Skeleton points within this fraction of either end are left out of the ridge test: at the tip
// and base the mask is cut and the DT does not see the blade's width.
constexpr float kRidgeTestMargin = 0.15f;

template <class V>
std::vector<V> resample(const std::vector<V>& polyline, int n) {
    if (n < 2)
        throw std::invalid_argument("resampleByArcLength: n must be >= 2, got " +
                                    std::to_string(n));
    if (polyline.empty()) throw std::invalid_argument("resampleByArcLength: empty polyline");
    std::vector<float> cumulative(polyline.size(), 0.f);
    for (std::size_t i = 1; i < polyline.size(); ++i)
        cumulative[i] = cumulative[i - 1] + glm::distance(polyline[i - 1], polyline[i]);
    const float total = cumulative.back();
    std::vector<V> out(static_cast<std::size_t>(n));
    if (total <= 0.f) {
        std::fill(out.begin(), out.end(), polyline.front());
        return out;
    }
    std::size_t seg = 0;
    for (int k = 0; k < n; ++k) {
        const float target = total * static_cast<float>(k) / static_cast<float>(n - 1);
        while (seg + 2 < polyline.size() && cumulative[seg + 1] < target) ++seg;
        if (polyline.size() == 1) {
            out[k] = polyline.front();
            continue;
        }
        const float len = cumulative[seg + 1] - cumulative[seg];
        const float f = len > 0.f ? std::clamp((target - cumulative[seg]) / len, 0.f, 1.f) : 0.f;
        out[k] = polyline[seg] + f * (polyline[seg + 1] - polyline[seg]);
    }
    out.front() = polyline.front();
    out.back() = polyline.back();
    return out;
}

// Moving average with a window that shrinks near the ends, so the base corners and the tip stay
// exactly where they are.
std::vector<glm::vec2> smoothSide(const std::vector<glm::vec2>& side) {
    const int n = static_cast<int>(side.size());
    std::vector<glm::vec2> out(side.size());
    for (int i = 0; i < n; ++i) {
        const int r = std::min({kSideSmoothingHalfWindow, i, n - 1 - i});
        glm::vec2 sum{0.f};
        for (int j = i - r; j <= i + r; ++j) sum += side[j];
        out[i] = sum / static_cast<float>(2 * r + 1);
    }
    return out;
}

float polylineLength(const std::vector<glm::vec2>& p) {
    float sum = 0.f;
    for (std::size_t i = 1; i < p.size(); ++i) sum += glm::distance(p[i - 1], p[i]);
    return sum;
}

float median(std::vector<float> v) {
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

glm::vec2 safeNormalize(glm::vec2 v, glm::vec2 fallback) {
    const float len = glm::length(v);
    return len > 1e-6f ? v / len : fallback;
}

// Median of the valid depth readings (metres) inside the blade mask in a square window of
// params.depthWindowRadius_px around (u, v), within [minDepth_m, maxDepth_m]; NaN when there is
// none. Restricting to the mask keeps the background out; the median keeps the minority of
// flying pixels on the blade's edge out.
float windowDepth_m(const capture::DepthFrame& frame, const capture::BladeContour& blade,
                    glm::vec2 p_px, const SkeletonParams& params) {
    const int r = params.depthWindowRadius_px;
    const float lowest_mm = params.minDepth_m * 1e3f;
    const float highest_mm = params.maxDepth_m > 0.f ? params.maxDepth_m * 1e3f : 1e9f;
    const bool useMask = !blade.mask.empty();
    const int u0 = static_cast<int>(std::lround(p_px.x)),
              v0 = static_cast<int>(std::lround(p_px.y));
    std::vector<float> values;
    for (int v = v0 - r; v <= v0 + r; ++v) {
        if (v < 0 || v >= frame.depth_mm.rows) continue;
        for (int u = u0 - r; u <= u0 + r; ++u) {
            if (u < 0 || u >= frame.depth_mm.cols) continue;
            if (useMask && !blade.covers({u, v})) continue;
            const std::uint16_t d = frame.depth_mm(v, u);
            if (d > 0 && d >= lowest_mm && d <= highest_mm)
                values.push_back(static_cast<float>(d) * 1e-3f);
        }
    }
    return values.empty() ? std::nanf("") : median(std::move(values));
}

// Least-squares line through (index, z) of the last `count` accepted readings met walking from
// `from` (exclusive) toward `step`'s opposite side, evaluated at index `at`. NaN when none.
float extrapolateAccepted(const std::vector<float>& z, const std::vector<bool>& accepted, int from,
                          int step, int count, int at) {
    const int n = static_cast<int>(z.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int m = 0;
    for (int j = from; j >= 0 && j < n && m < count; j -= step) {
        if (!accepted[static_cast<std::size_t>(j)]) continue;
        const double x = j - at;
        sx += x, sy += z[static_cast<std::size_t>(j)], sxx += x * x;
        sxy += x * z[static_cast<std::size_t>(j)];
        ++m;
    }
    if (m == 0) return std::nanf("");
    const double det = m * sxx - sx * sx;
    // Intercept at x = 0 (the index `at`); one reading, or all at one index: constant.
    return det > 1e-9 ? static_cast<float>((sxx * sy - sx * sxy) / det)
                      : static_cast<float>(sy / m);
}

// Drops flying pixels and hole edges, then fills every gap along the chain. Returns how many
// entries were filled.
//
// Readings are accepted outward from the reliable middle of the chain: in the middle
// (kReliableMiddleFraction of it) a reading is kept when it is within maxJump_m of the centred
// running median of its neighbours; from there, walking to each end, a reading is kept when it is
// within maxJump_m of the line through the last accepted readings (kEndExtrapolationFraction of
// the chain), extrapolated to it. A centred median cannot do this at the ends: its window turns
// one-sided there, and at a thin tip most readings are flying pixels (depth between the blade and
// the wall behind it), so the median is itself a flying pixel and would lift the tip toward the
// wall.
//
// Gaps between accepted readings are filled by linear interpolation along the chain; beyond the
// outermost accepted reading by the same line extrapolated, so a blade tilted in depth keeps
// its slope to the end.
int rejectAndFill(std::vector<float>& z, float maxJump_m) {
    const int n = static_cast<int>(z.size());
    std::vector<bool> accepted(z.size(), false);
    const int margin = static_cast<int>(
        std::lround(0.5f * (1.f - kReliableMiddleFraction) * static_cast<float>(n)));
    int lo = std::clamp(margin, 0, n - 1), hi = std::clamp(n - 1 - margin, lo, n - 1);
    const auto medianTest = [&](int i) {
        if (std::isnan(z[static_cast<std::size_t>(i)])) return false;
        std::vector<float> window;
        for (int j = std::max(0, i - kDepthMedianHalfWindow);
             j <= std::min(n - 1, i + kDepthMedianHalfWindow); ++j)
            if (!std::isnan(z[static_cast<std::size_t>(j)]))
                window.push_back(z[static_cast<std::size_t>(j)]);
        return std::abs(z[static_cast<std::size_t>(i)] - median(window)) <= maxJump_m;
    };
    bool any = false;
    for (int i = lo; i <= hi; ++i) any |= (accepted[static_cast<std::size_t>(i)] = medianTest(i));
    if (!any) {
        // Nothing reliable in the middle (a blade mostly without depth): the running median over
        // the whole chain is the best there is.
        for (int i = 0; i < n; ++i) accepted[static_cast<std::size_t>(i)] = medianTest(i);
        lo = 0, hi = n - 1;
    }
    const int count =
        std::max(kMinExtrapolationPoints,
                 static_cast<int>(std::lround(kEndExtrapolationFraction * static_cast<float>(n))));
    for (const int step : {1, -1}) {
        for (int i = step > 0 ? hi + 1 : lo - 1; i >= 0 && i < n; i += step) {
            if (std::isnan(z[static_cast<std::size_t>(i)])) continue;
            const float predicted = extrapolateAccepted(z, accepted, i - step, step, count, i);
            accepted[static_cast<std::size_t>(i)] =
                std::isnan(predicted) ||
                std::abs(z[static_cast<std::size_t>(i)] - predicted) <= maxJump_m;
        }
    }

    int first = -1, last = -1;
    for (int i = 0; i < n; ++i)
        if (accepted[static_cast<std::size_t>(i)]) {
            if (first < 0) first = i;
            last = i;
        }
    if (first < 0) return n;  // nothing valid; caller throws
    std::vector<float> cleaned(z.size());
    int filled = 0;
    for (int i = 0; i < n; ++i) {
        if (accepted[static_cast<std::size_t>(i)]) {
            cleaned[static_cast<std::size_t>(i)] = z[static_cast<std::size_t>(i)];
            continue;
        }
        ++filled;
        if (i < first) {
            cleaned[static_cast<std::size_t>(i)] =
                extrapolateAccepted(z, accepted, first, -1, count, i);
        } else if (i > last) {
            cleaned[static_cast<std::size_t>(i)] =
                extrapolateAccepted(z, accepted, last, 1, count, i);
        } else {
            int a = i - 1, b = i + 1;
            while (!accepted[static_cast<std::size_t>(a)]) --a;
            while (!accepted[static_cast<std::size_t>(b)]) ++b;
            const float f = static_cast<float>(i - a) / static_cast<float>(b - a);
            cleaned[static_cast<std::size_t>(i)] =
                z[static_cast<std::size_t>(a)] * (1.f - f) + z[static_cast<std::size_t>(b)] * f;
        }
    }
    z = std::move(cleaned);
    return filled;
}

// Local linear regression of depth against the chain index over a window of +-h points: smooths
// sensor noise and quantisation steps while following the blade's slope in depth.
std::vector<float> regressDepth(const std::vector<float>& z, int h) {
    const int n = static_cast<int>(z.size());
    std::vector<float> out(z.size());
    for (int i = 0; i < n; ++i) {
        const int lo = std::max(0, i - h), hi = std::min(n - 1, i + h);
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        const double m = hi - lo + 1;
        for (int j = lo; j <= hi; ++j) {
            const double x = j - i;
            sx += x, sy += z[j], sxx += x * x, sxy += x * z[j];
        }
        const double det = m * sxx - sx * sx;
        // Intercept at x = 0 (the point itself) of the least-squares line.
        out[i] = det > 1e-9 ? static_cast<float>((sxx * sy - sx * sxy) / det)
                            : static_cast<float>(sy / m);
    }
    return out;
}

// Depth slope across the blade at one midline point (metres of depth per pixel across, side A
// -> side B): least squares of depth on the lateral offset over the blade's pixels within
// kTiltHalfLength_px along the blade and inside its width less kTiltEdgeMargin_px at each side,
// where pixels mix the blade with what lies behind it. Readings further than maxDepthJump_m from
// the point's depth belong to something else. NaN when too few pixels or too narrow a spread.
constexpr float kTiltHalfLength_px = 1.5f;
constexpr float kTiltEdgeMargin_px = 1.f;
constexpr int kMinTiltReadings = 5;
constexpr float kMinTiltSpread_px = 2.5f;
float acrossDepthSlope_mPerPx(const capture::DepthFrame& frame, const capture::BladeContour& blade,
                              glm::vec2 mid_px, glm::vec2 across, float width_px,
                              float centreDepth_m, const SkeletonParams& params) {
    const float halfLateral = 0.5f * width_px - kTiltEdgeMargin_px;
    if (!(halfLateral > 0.5f * kMinTiltSpread_px) || !std::isfinite(centreDepth_m))
        return std::nanf("");
    const glm::vec2 along{-across.y, across.x};
    const int r = static_cast<int>(std::ceil(halfLateral + kTiltHalfLength_px));
    const int u0 = static_cast<int>(std::lround(mid_px.x)),
              v0 = static_cast<int>(std::lround(mid_px.y));
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int m = 0;
    float lo = 1e9f, hi = -1e9f;
    for (int v = std::max(0, v0 - r); v <= std::min(frame.depth_mm.rows - 1, v0 + r); ++v)
        for (int u = std::max(0, u0 - r); u <= std::min(frame.depth_mm.cols - 1, u0 + r); ++u) {
            const glm::vec2 offset =
                glm::vec2(static_cast<float>(u), static_cast<float>(v)) - mid_px;
            const float lateral = glm::dot(offset, across);
            if (std::abs(glm::dot(offset, along)) > kTiltHalfLength_px ||
                std::abs(lateral) > halfLateral)
                continue;
            if (!blade.mask.empty() && !blade.covers({u, v})) continue;
            const std::uint16_t d = frame.depth_mm(v, u);
            const float z = static_cast<float>(d) * 1e-3f;
            if (d == 0 || std::abs(z - centreDepth_m) > params.maxDepthJump_m) continue;
            sx += lateral, sy += z, sxx += lateral * lateral, sxy += lateral * z;
            lo = std::min(lo, lateral), hi = std::max(hi, lateral);
            ++m;
        }
    const double det = m * sxx - sx * sx;
    if (m < kMinTiltReadings || hi - lo < kMinTiltSpread_px || !(det > 1e-9)) return std::nanf("");
    return static_cast<float>((m * sxy - sx * sy) / det);
}

}  // namespace

std::vector<glm::vec2> resampleByArcLength(const std::vector<glm::vec2>& polyline, int n) {
    return resample(polyline, n);
}
std::vector<glm::vec3> resampleByArcLength(const std::vector<glm::vec3>& polyline, int n) {
    return resample(polyline, n);
}

std::vector<float> smoothWidths(const std::vector<float>& width, int passes) {
    const std::size_t n = width.size();
    if (n < 3) return width;
    std::vector<float> w = width;
    for (std::size_t i = 1; i + 1 < n; ++i) w[i] = median({width[i - 1], width[i], width[i + 1]});
    for (int p = 0; p < passes; ++p) {
        std::vector<float> next = w;
        for (std::size_t i = 1; i + 1 < n; ++i)
            next[i] = 0.25f * w[i - 1] + 0.5f * w[i] + 0.25f * w[i + 1];
        w = std::move(next);
    }
    return w;
}

Skeleton matchSymmetricContour(const capture::BladeContour& blade, const SkeletonParams& params) {
    const int count = static_cast<int>(blade.contour_px.size());
    if (count < 3 || blade.tipIndex <= 0 || blade.tipIndex >= count - 1)
        throw std::invalid_argument(
            "matchSymmetricContour: need >= 3 contour points and 0 < tipIndex < " +
            std::to_string(count - 1) + ", got " + std::to_string(count) + " points, tipIndex " +
            std::to_string(blade.tipIndex));
    if (params.points < 3)
        throw std::invalid_argument("matchSymmetricContour: params.points must be >= 3, got " +
                                    std::to_string(params.points));
    std::vector<glm::vec2> sideA, sideB;
    for (int i = 0; i <= blade.tipIndex; ++i)
        sideA.emplace_back(static_cast<float>(blade.contour_px[i].x),
                           static_cast<float>(blade.contour_px[i].y));
    for (int i = count - 1; i >= blade.tipIndex; --i)
        sideB.emplace_back(static_cast<float>(blade.contour_px[i].x),
                           static_cast<float>(blade.contour_px[i].y));

    sideA = smoothSide(sideA);
    sideB = smoothSide(sideB);
    Skeleton s;
    const float lengthA = polylineLength(sideA), lengthB = polylineLength(sideB);
    s.sideLengthRatio = std::max(lengthA, lengthB) / std::max(std::min(lengthA, lengthB), 1e-6f);

    const int n = params.points;
    const std::vector<glm::vec2> a = resample(sideA, n), b = resample(sideB, n);
    std::vector<float> rawWidth(static_cast<std::size_t>(n));
    s.midline_px.resize(static_cast<std::size_t>(n));
    s.across_px.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) s.midline_px[i] = 0.5f * (a[i] + b[i]);
    // Pairing by arc-length fraction drifts along the blade where curvature times width varies
    // (the inner side is shorter than the outer one locally, not uniformly), so a matched pair is
    // not straight across and its length overstates the width. The width is therefore the
    // pair's extent across the midline, |(b - a) . n| with n the midline's normal.
    const int h = std::max(
        1, static_cast<int>(std::lround(kTangentHalfWindowFraction * static_cast<float>(n - 1))));
    for (int i = 0; i < n; ++i) {
        const glm::vec2 tangent = safeNormalize(
            s.midline_px[std::min(n - 1, i + h)] - s.midline_px[std::max(0, i - h)], {0.f, -1.f});
        glm::vec2 normal{-tangent.y, tangent.x};
        if (glm::dot(normal, b[i] - a[i]) < 0.f) normal = -normal;  // side A -> side B
        s.across_px[i] = normal;
        rawWidth[i] =
            i == n - 1 ? 0.f : std::abs(glm::dot(b[i] - a[i], normal)) + kBoundaryFootprint_px;
    }
    s.width_px = smoothWidths(rawWidth, params.widthSmoothingPasses);
    s.width_px.back() = 0.f;

    // Half-pixel extension of both ends along the chain's end tangents (see kHalfPixel_px).
    const int k =
        std::max(1, static_cast<int>(std::lround(kEndTangentFraction * static_cast<float>(n - 1))));
    const glm::vec2 baseTangent = safeNormalize(s.midline_px[0] - s.midline_px[k], {0.f, 1.f});
    const glm::vec2 tipTangent =
        safeNormalize(s.midline_px[n - 1] - s.midline_px[n - 1 - k], {0.f, -1.f});
    s.midline_px.front() += kHalfPixel_px * baseTangent;
    s.midline_px.back() += kHalfPixel_px * tipTangent;

    if (s.sideLengthRatio > params.maxSideLengthRatio) {
        s.asymmetric = true;
        s.reasons.push_back("contour sides differ in length by a factor " +
                            std::to_string(s.sideLengthRatio) + " (> " +
                            std::to_string(params.maxSideLengthRatio) + ")");
    }
    if (!blade.mask.empty()) {
        const std::vector<float> dtWidth =
            distanceTransformWidth_px(blade.mask, s.midline_px, blade.maskOrigin_px);
        double sum = 0.0;
        int used = 0;
        for (int i = 0; i < n; ++i) {
            const float f = static_cast<float>(i) / static_cast<float>(n - 1);
            if (f < kRidgeTestMargin || f > 1.f - kRidgeTestMargin || s.width_px[i] <= 0.f)
                continue;
            sum += std::abs(dtWidth[i] - s.width_px[i]) / s.width_px[i];
            ++used;
        }
        s.ridgeOffsetFraction = used > 0 ? static_cast<float>(sum / used) : 0.f;
        if (s.ridgeOffsetFraction > params.maxRidgeOffsetFraction) {
            s.asymmetric = true;
            s.reasons.push_back("midline is off the distance-transform ridge by " +
                                std::to_string(s.ridgeOffsetFraction) + " of the half width (> " +
                                std::to_string(params.maxRidgeOffsetFraction) + ")");
        }
    }
    return s;
}

Skeleton extractSkeleton(const capture::BladeContour& blade, const capture::DepthFrame& frame,
                         const SkeletonParams& params) {
    if (frame.depth_mm.empty()) throw std::invalid_argument("extractSkeleton: empty depth frame");
    if (!blade.mask.empty() &&
        (blade.maskBox_px() & cv::Rect(0, 0, frame.depth_mm.cols, frame.depth_mm.rows)) !=
            blade.maskBox_px())
        throw std::invalid_argument("extractSkeleton: the blade mask reaches outside the frame");
    Skeleton s = matchSymmetricContour(blade, params);
    const int n = static_cast<int>(s.midline_px.size());

    std::vector<float> z(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) z[i] = windowDepth_m(frame, blade, s.midline_px[i], params);
    s.filledDepths = rejectAndFill(z, params.maxDepthJump_m);
    if (s.filledDepths >= n)
        throw ModelingError(
            "extractSkeleton: blade " + std::to_string(blade.id) + " of frame " +
            std::to_string(frame.index) +
            " has no depth reading inside its mask; check the mask or the depth band");
    const int h = std::max(
        2, static_cast<int>(std::lround(kDepthRegressionFraction * static_cast<float>(n))));
    s.depth_m = regressDepth(z, h);

    const capture::Intrinsics& K = frame.intrinsics;
    s.points_m.resize(static_cast<std::size_t>(n));
    s.width_m.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        s.points_m[i] = K.backProject(s.midline_px[i].x, s.midline_px[i].y, s.depth_m[i]);
        // The width is measured across the blade in the image; at the point's depth one pixel
        // spans z / f metres along each image axis.
        const glm::vec2 acrossPerPixel_m{s.across_px[i].x * s.depth_m[i] / K.fx_px,
                                         s.across_px[i].y * s.depth_m[i] / K.fy_px};
        s.width_m[i] = s.width_px[i] * glm::length(acrossPerPixel_m);
    }
    s.acrossStep_m.assign(static_cast<std::size_t>(n), glm::vec3(0.f));
    for (int i = 0; i < n; ++i) {
        const float slope = acrossDepthSlope_mPerPx(frame, blade, s.midline_px[i], s.across_px[i],
                                                    s.width_px[i], s.depth_m[i], params);
        if (std::isfinite(slope))
            s.acrossStep_m[i] = {s.across_px[i].x * s.depth_m[i] / K.fx_px,
                                 s.across_px[i].y * s.depth_m[i] / K.fy_px, slope};
    }
    s.arcFraction.assign(static_cast<std::size_t>(n), 0.f);
    for (int i = 1; i < n; ++i)
        s.arcFraction[i] = s.arcFraction[i - 1] + glm::distance(s.points_m[i - 1], s.points_m[i]);
    const float total = s.arcFraction.back();
    for (float& f : s.arcFraction) f = total > 0.f ? f / total : 0.f;
    return s;
}

}  // namespace meadow::modeling
