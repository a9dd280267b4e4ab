// Whether the blade model holds a centre line (capture/src/segmentation/polyline.cpp,
// quadraticBezierMiss_px): the curl flag asks it before flagging a blade that turns far.
#include <gtest/gtest.h>

#include <cmath>

#include "segmentation/polyline.h"

namespace meadow::capture::segmentation {
namespace {

std::vector<cv::Point2f> sampled(int count, const std::function<cv::Point2f(float)>& at) {
    std::vector<cv::Point2f> line;
    for (int i = 0; i < count; ++i) line.push_back(at(static_cast<float>(i) / (count - 1)));
    return line;
}

float length(const std::vector<cv::Point2f>& line) {
    float l = 0.f;
    for (std::size_t i = 1; i < line.size(); ++i)
        l += static_cast<float>(cv::norm(line[i] - line[i - 1]));
    return l;
}

TEST(QuadraticBezierMiss, AQuadraticIsHeldExactly) {
    const cv::Point2f p0(0, 0), p1(40, -300), p2(120, 20);  // rises and droops: turns > 150 deg
    const auto line = sampled(
        8, [&](float t) { return (1 - t) * (1 - t) * p0 + 2 * t * (1 - t) * p1 + t * t * p2; });
    EXPECT_LT(quadraticBezierMiss_px(line), 0.03f * length(line));
}

TEST(QuadraticBezierMiss, AnArchingLeafFitsAndACurlDoesNot) {
    // A leaf rising 200 px and hanging 120 px down again beside itself: a parabola-like arch.
    const auto arch = sampled(8, [](float t) {
        return cv::Point2f(100.f * t, -200.f * std::sin(static_cast<float>(M_PI) * 0.8f * t));
    });
    EXPECT_LT(quadraticBezierMiss_px(arch), 0.08f * length(arch));
    // A leaf curling round three quarters of a circle: no quadratic turns that far.
    const auto curl = sampled(8, [](float t) {
        const float a = 1.5f * static_cast<float>(M_PI) * t;
        return cv::Point2f(60.f * std::sin(a), -60.f * (1.f - std::cos(a)));
    });
    EXPECT_GT(quadraticBezierMiss_px(curl), 0.08f * length(curl));
    EXPECT_EQ(quadraticBezierMiss_px({{0, 0}, {5, 5}}), 0.f);
}

}  // namespace
}  // namespace meadow::capture::segmentation
