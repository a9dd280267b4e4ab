#pragma once
// Synthetic ground truth for the modeling tests: a known blade (quadratic Bezier spine + width
// profile, its face a plane in camera space) drawn with OpenCV into a mask, an ordered contour
// (base side A -> tip -> base side B) and a depth frame at known intrinsics.
#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "meadow/capture/blade_contour.h"
#include "meadow/capture/depth_frame.h"
#include "meadow/modeling/quadratic_bezier.h"

namespace meadow::modeling::test {

struct SyntheticBlade {
    QuadraticBezier spine_m;               // camera space
    std::function<float(float)> width;     // full width (m) at arc fraction s
    glm::vec3 faceNormal{0.f, 0.f, -1.f};  // toward the camera
    float maxWidth_m = 0.f;
};

struct SyntheticView {
    capture::BladeContour blade;
    capture::DepthFrame frame;
};

// A higher-resolution camera than the Kinect, so that the noise-free tests measure the method,
// not the pixel grid: 0.33 mm per pixel at 0.5 m.
inline capture::Intrinsics fineIntrinsics() {
    return {.width_px = 1280,
            .height_px = 1024,
            .fx_px = 1500.f,
            .fy_px = 1500.f,
            .cx_px = 639.5f,
            .cy_px = 511.5f};
}

// A blade rooted at (x, y, z) (camera space, metres) growing up the image (-y), bending toward
// +x by `bend` (tip offset / height), `height_m` tall, width profile 1 - s^2 style with a base.
inline SyntheticBlade makeBlade(glm::vec3 root_m, float height_m, float bend, float baseWidth_m,
                                float depthSlope = 0.f) {
    SyntheticBlade b;
    // The face tilts in depth by depthSlope (dz per metre of height) around the x axis.
    const glm::vec3 up = glm::normalize(glm::vec3(0.f, -1.f, depthSlope));
    const glm::vec3 side{1.f, 0.f, 0.f};
    b.faceNormal = glm::normalize(glm::cross(up, side));
    if (b.faceNormal.z > 0.f) b.faceNormal = -b.faceNormal;
    b.spine_m.v0 = root_m;
    b.spine_m.v1 = root_m + 0.55f * height_m * up + 0.05f * bend * height_m * side;
    b.spine_m.v2 = root_m + (1.f - 0.5f * bend * bend) * height_m * up + bend * height_m * side;
    b.width = [baseWidth_m](float s) {
        return baseWidth_m * (1.f - 0.85f * s * s) * (s < 1.f ? 1.f : 0.f);
    };
    b.maxWidth_m = baseWidth_m;
    return b;
}

// Renders the blade: filled polygon (subpixel), depth from the face plane, background far behind.
inline SyntheticView renderBlade(const SyntheticBlade& b, const capture::Intrinsics& K,
                                 float backgroundDepth_m = 0.f) {
    constexpr int kSamples = 600;
    std::vector<glm::vec3> left, right;
    for (int i = 0; i <= kSamples; ++i) {
        const float s = static_cast<float>(i) / kSamples;
        const float t = b.spine_m.parameterAtLengthFraction(s);
        const glm::vec3 c = b.spine_m.at(t);
        const glm::vec3 across =
            glm::normalize(glm::cross(b.faceNormal, glm::normalize(b.spine_m.tangent(t))));
        const float w = i == kSamples ? 0.f : b.width(s);
        left.push_back(c - 0.5f * w * across);
        right.push_back(c + 0.5f * w * across);
    }
    // A pixel belongs to the blade when its centre is inside the outline, as a point-sampling
    // rasteriser decides (cv::fillPoly would also fill every pixel the outline touches, which
    // widens a blade by about a pixel).
    std::vector<cv::Point2f> polygon;
    for (const glm::vec3& p : left) {
        const glm::vec2 q = K.project(p);
        polygon.emplace_back(q.x, q.y);
    }
    for (auto it = right.rbegin() + 1; it != right.rend(); ++it) {
        const glm::vec2 q = K.project(*it);
        polygon.emplace_back(q.x, q.y);
    }
    SyntheticView view;
    cv::Mat1b mask = cv::Mat1b::zeros(K.height_px, K.width_px);
    const cv::Rect box = cv::boundingRect(polygon) & cv::Rect(0, 0, K.width_px, K.height_px);
    for (int v = box.y; v < box.y + box.height; ++v)
        for (int u = box.x; u < box.x + box.width; ++u)
            if (cv::pointPolygonTest(
                    polygon, cv::Point2f(static_cast<float>(u), static_cast<float>(v)), false) > 0)
                mask(v, u) = 255;

    view.frame.intrinsics = K;
    view.frame.depth_mm = cv::Mat1w::zeros(K.height_px, K.width_px);
    const float planeOffset = glm::dot(b.faceNormal, b.spine_m.v0);
    for (int v = 0; v < K.height_px; ++v)
        for (int u = 0; u < K.width_px; ++u) {
            float z = backgroundDepth_m;
            if (mask(v, u)) {
                const glm::vec3 ray{(u - K.cx_px) / K.fx_px, (v - K.cy_px) / K.fy_px, 1.f};
                z = planeOffset / glm::dot(b.faceNormal, ray);
            }
            view.frame.depth_mm(v, u) = static_cast<std::uint16_t>(std::lround(z * 1000.f));
        }

    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    if (contours.empty()) throw std::runtime_error("renderBlade: blade not visible");
    const auto& c =
        *std::max_element(contours.begin(), contours.end(),
                          [](const auto& x, const auto& y) { return x.size() < y.size(); });
    const auto nearest = [&](const glm::vec3& p) {
        const glm::vec2 q = K.project(p);
        int best = 0;
        float bestD = 1e30f;
        for (int i = 0; i < static_cast<int>(c.size()); ++i) {
            const float d = glm::distance(q, glm::vec2(c[i].x, c[i].y));
            if (d < bestD) bestD = d, best = i;
        }
        return best;
    };
    const int n = static_cast<int>(c.size());
    const int a = nearest(left.front()), tip = nearest(left.back()), bb = nearest(right.front());
    // Walk from A in the direction that meets the tip before B.
    int step = 1;
    for (int i = a, k = 0; k < n; ++k, i = (i + 1) % n) {
        if (i == bb) {
            step = -1;
            break;
        }
        if (i == tip) break;
    }
    view.blade.id = 1;
    view.blade.mask = mask;
    for (int i = a;; i = (i + step + n) % n) {
        if (i == tip) view.blade.tipIndex = static_cast<int>(view.blade.contour_px.size());
        view.blade.contour_px.push_back(c[i]);
        if (i == bb) break;
    }
    return view;
}

// Largest distance (m) from points to the truth spine (dense sampling of the curve).
inline float maxDistanceToSpine_m(const std::vector<glm::vec3>& points,
                                  const QuadraticBezier& spine) {
    constexpr int kCurveSamples = 2000;
    float worst = 0.f;
    for (const glm::vec3& p : points) {
        float best = 1e30f;
        for (int i = 0; i <= kCurveSamples; ++i)
            best =
                std::min(best, glm::distance(p, spine.at(static_cast<float>(i) / kCurveSamples)));
        worst = std::max(worst, best);
    }
    return worst;
}

}  // namespace meadow::modeling::test
