// Independent width estimate from the distance transform of the blade mask (no contour
// matching involved), used to check the expansion widths and to detect an off-ridge midline.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "meadow/modeling/skeleton.h"

namespace meadow::modeling {
namespace {

// DT value d at the centre pixel of a blade w pixels wide (w odd) is (w + 1) / 2: centre pixel
// to the first background pixel centre, so w = 2 d - 1 on the ridge. But the midline sits at an
// arbitrary sub-pixel position and bilinear sampling of the DT's roof there loses about as much
// (on synthetic blades 2 d - 1 reads low and 2 d about right). So w ~ 2 d.
constexpr float kCentreToBackground_px = 0.f;

float bilinear(const cv::Mat1f& img, glm::vec2 p) {
    const float x = std::clamp(p.x, 0.f, static_cast<float>(img.cols - 1));
    const float y = std::clamp(p.y, 0.f, static_cast<float>(img.rows - 1));
    const int x0 = std::min(static_cast<int>(x), img.cols - 2 < 0 ? 0 : img.cols - 2);
    const int y0 = std::min(static_cast<int>(y), img.rows - 2 < 0 ? 0 : img.rows - 2);
    const int x1 = std::min(x0 + 1, img.cols - 1), y1 = std::min(y0 + 1, img.rows - 1);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    return (img(y0, x0) * (1 - fx) + img(y0, x1) * fx) * (1 - fy) +
           (img(y1, x0) * (1 - fx) + img(y1, x1) * fx) * fy;
}

}  // namespace

std::vector<float> distanceTransformWidth_px(const cv::Mat1b& mask,
                                             const std::vector<glm::vec2>& midline_px,
                                             cv::Point maskOrigin_px) {
    if (mask.empty()) throw std::invalid_argument("distanceTransformWidth_px: empty mask");
    // Pad by one background pixel so a blade touching the image border still has a boundary.
    cv::Mat1b padded;
    cv::copyMakeBorder(mask, padded, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    cv::Mat1f dt;
    cv::distanceTransform(padded, dt, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    std::vector<float> out;
    out.reserve(midline_px.size());
    // Frame pixel p is padded pixel p - origin + 1. Outside the padded box the DT is 0, as on
    // the background of a frame-sized mask; bilinear() clamps to the border, which is 0.
    const glm::vec2 toPadded = glm::vec2(1.f) - glm::vec2(maskOrigin_px.x, maskOrigin_px.y);
    for (const glm::vec2& p : midline_px)
        out.push_back(std::max(0.f, 2.f * bilinear(dt, p + toPadded) - kCentreToBackground_px));
    return out;
}

}  // namespace meadow::modeling
