// Edge smoothing along the contour. Lateral sensor noise moves each edge pixel on its own by
// ~0.8 px, so the mask's edge is a blade's true edge plus independent per-pixel jitter. A blur
// of the mask averages only a pixel's 2-3 edge neighbours; a blade's edge is smooth over tens
// of pixels, so averaging the contour's points along its length estimates it better
// (see docs/capture.md#clean-up-and-edge-smoothing).
// Four guards keep what is not jitter:
// - no point moves more than maxShift_px (the jitter is about a pixel);
// - a neighbour counts in a point's average only as far as it runs the same way, so the two
//   sides of a tip or of a valley between blades are not averaged into each other;
// - a point with too little of its average left (a corner: a tip, a valley) stays put;
// - parts under 3 px wide are left as they were.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {
// A contour point is the centre of a boundary pixel (one with a 4-neighbour outside). Over a
// straight edge with unit normal n those centres lie, on average, half the pixel pitch along n
// inside the edge, max(|n.x|, |n.y|) / 2: 0.5 px on an axis-aligned edge, 0.35 px at 45 deg.
constexpr float kHalfPixel = 0.5f;
// A point's direction: the chord between the points this far either side of it.
constexpr int kTangentSpan = 3;
// Weight of a neighbour whose direction differs by angle a: cos(a)^4 (30 deg: 0.56, 45 deg:
// 0.25, beyond 90 deg: 0), times the Gaussian.
constexpr int kTangentSharpness = 4;
// Below this share of its Gaussian weight left, a point is at a corner and is not moved.
// Chosen on the leaf presets without noise, where an exact mask should come back as it was:
// without the threshold tips and valleys are rounded off.
constexpr float kMinWeightShare = 0.5f;

float power(float x, int n) {
    float r = 1.f;
    for (int i = 0; i < n; ++i) r *= x;
    return r;
}

// The edge the contour's pixels stand for: the points averaged along the contour (closed) as
// the file comment says, then moved out to the edge (kHalfPixel).
std::vector<cv::Point2f> smoothedEdge(const std::vector<cv::Point>& contour, bool hole,
                                      const std::vector<float>& kernel, float maxShift_px) {
    const int n = static_cast<int>(contour.size());
    const int radius = n >= static_cast<int>(kernel.size()) ? static_cast<int>(kernel.size() / 2)
                                                            : 0;  // too short to average
    // The closed contour laid out with `pad` points of wrap-around either side: p[pad + i] is
    // point i, for i in [-pad, n + pad).
    const int pad = std::max(radius, kTangentSpan);
    std::vector<cv::Point2f> p(static_cast<size_t>(n + 2 * pad));
    for (int i = -pad; i < n + pad; ++i)
        p[static_cast<size_t>(i + pad)] =
            cv::Point2f(contour[static_cast<size_t>((i % n + n) % n)]);
    std::vector<cv::Point2f> direction(p.size());
    for (int i = kTangentSpan; i + kTangentSpan < static_cast<int>(p.size()); ++i) {
        const cv::Point2f t =
            p[static_cast<size_t>(i + kTangentSpan)] - p[static_cast<size_t>(i - kTangentSpan)];
        const float len = std::hypot(t.x, t.y);
        direction[static_cast<size_t>(i)] = len > 0.f ? t / len : cv::Point2f(0.f, 0.f);
    }
    std::vector<cv::Point2f> s(contour.size());
    for (int i = 0; i < n; ++i) {
        const size_t c = static_cast<size_t>(i + pad);
        cv::Point2f sum(0.f, 0.f);
        float weight = 0.f;
        for (int k = -radius; k <= radius; ++k) {
            const size_t j = c + static_cast<size_t>(k + radius) - static_cast<size_t>(radius);
            const float along = std::max(0.f, direction[c].dot(direction[j]));
            const float w =
                kernel[static_cast<size_t>(k + radius)] * power(along, kTangentSharpness);
            sum += w * p[j];
            weight += w;
        }
        cv::Point2f d(0.f, 0.f);
        if (radius > 0 && weight >= kMinWeightShare) d = sum / weight - p[c];
        const float len = std::hypot(d.x, d.y);
        if (len > maxShift_px) d *= maxShift_px / len;
        s[static_cast<size_t>(i)] = p[c] + d;
    }
    // Away from the foreground: out of an outer contour's polygon, into a hole's. The sign of
    // the oriented area says which way the polygon runs, hence which side is its inside.
    const float side =
        (cv::contourArea(contour, /*oriented=*/true) > 0 ? 1.f : -1.f) * (hole ? -1.f : 1.f);
    std::vector<cv::Point2f> edge(contour.size());
    for (int i = 0; i < n; ++i) {
        const cv::Point2f t =
            s[static_cast<size_t>((i + 1) % n)] - s[static_cast<size_t>((i + n - 1) % n)];
        const float len = std::hypot(t.x, t.y);
        edge[static_cast<size_t>(i)] = s[static_cast<size_t>(i)];
        if (len > 0.f) {
            const cv::Point2f normal = side / len * cv::Point2f(t.y, -t.x);
            edge[static_cast<size_t>(i)] +=
                kHalfPixel * std::max(std::abs(normal.x), std::abs(normal.y)) * normal;
        }
    }
    return edge;
}

// Sets the pixels whose centres lie strictly inside the polygons, by non-zero winding (holes
// wind opposite to outer contours; two outer contours that overlap stay filled). cv::fillPoly
// also sets every pixel its edges pass through, which would move a sub-pixel edge outwards by
// up to half a pixel, more on steep edges than on flat ones.
void fillPixelCentresInside(cv::Mat1b& mask, const std::vector<std::vector<cv::Point2f>>& polys) {
    struct Crossing {
        float x;
        int winding;
    };
    std::vector<std::vector<Crossing>> rows(static_cast<size_t>(mask.rows));
    for (const auto& poly : polys)
        for (size_t i = 0; i < poly.size(); ++i) {
            const cv::Point2f a = poly[i], b = poly[(i + 1) % poly.size()];
            if (a.y == b.y) continue;
            // Rows whose centre lies in [low, high): a vertex shared by two edges counts once.
            const float low = std::min(a.y, b.y), high = std::max(a.y, b.y);
            const int y0 = std::max(0, static_cast<int>(std::ceil(low)));
            const int y1 = std::min(mask.rows - 1, static_cast<int>(std::ceil(high)) - 1);
            for (int y = y0; y <= y1; ++y) {
                const float t = (static_cast<float>(y) - a.y) / (b.y - a.y);
                rows[static_cast<size_t>(y)].push_back({a.x + t * (b.x - a.x), b.y > a.y ? 1 : -1});
            }
        }
    for (int y = 0; y < mask.rows; ++y) {
        auto& r = rows[static_cast<size_t>(y)];
        std::sort(r.begin(), r.end(),
                  [](const Crossing& p, const Crossing& q) { return p.x < q.x; });
        int winding = 0;
        for (size_t i = 0; i + 1 < r.size(); ++i) {
            winding += r[i].winding;
            if (winding == 0) continue;
            const int x0 = std::max(0, static_cast<int>(std::floor(r[i].x)) + 1);
            const int x1 = std::min(mask.cols - 1, static_cast<int>(std::ceil(r[i + 1].x)) - 1);
            for (int x = x0; x <= x1; ++x) mask(y, x) = 255;
        }
    }
}
}  // namespace

void smoothContours(cv::Mat1b& mask, float sigma_px, float maxShift_px, StageReport& report) {
    if (sigma_px <= 0.f || maxShift_px <= 0.f) return;
    std::vector<std::vector<cv::Point>> contours;
    std::vector<cv::Vec4i> hierarchy;  // two levels: outer contours, and holes with a parent
    cv::findContours(mask.clone(), contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_NONE);
    const int radius = static_cast<int>(std::ceil(3.f * sigma_px));
    const cv::Mat1f gaussian = cv::getGaussianKernel(2 * radius + 1, sigma_px, CV_32F);
    const std::vector<float> kernel(gaussian.begin(), gaussian.end());
    std::vector<std::vector<cv::Point2f>> edges;
    std::vector<std::vector<cv::Point>> specks;  // one or two pixels: no area to fill
    for (size_t i = 0; i < contours.size(); ++i) {
        if (contours[i].size() < 3)
            specks.push_back(std::move(contours[i]));
        else
            edges.push_back(smoothedEdge(contours[i], hierarchy[i][3] >= 0, kernel, maxShift_px));
    }
    const int before = cv::countNonZero(mask);
    const cv::Mat1b original = mask.clone();
    mask.setTo(0);
    fillPixelCentresInside(mask, edges);
    for (const auto& speck : specks)
        for (const auto& p : speck) mask(p) = 255;
    // Parts under 3 px wide (what a 3x3 opening removes, and not within a pixel of what it
    // keeps) stay as they were, foreground and background alike: a one-pixel line's staircase
    // is its shape, not jitter, and the straightened line would drop its corner pixels; a slit
    // between two blades would close where both its sides moved in.
    const cv::Mat cross = cv::getStructuringElement(cv::MORPH_ELLIPSE, {3, 3});
    const auto thinParts = [&](const cv::Mat1b& m) {
        cv::Mat1b thick;
        cv::morphologyEx(m, thick, cv::MORPH_OPEN, cross);
        cv::dilate(thick, thick, cross);
        return cv::Mat1b(m & ~thick);
    };
    mask |= thinParts(original);
    mask &= ~thinParts(~original);
    report.notes.push_back("edge smoothing (sigma " + std::to_string(sigma_px).substr(0, 4) +
                           " px along the contour): " + std::to_string(before) + " -> " +
                           std::to_string(cv::countNonZero(mask)) + " px");
}

}  // namespace meadow::capture::segmentation
