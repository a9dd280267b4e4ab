#pragma once
// Image measures of rendered meadows: which pixels are grass.
#include <opencv2/core/mat.hpp>

namespace meadow::test {

// A pixel is grass when its green is clearly above its red and blue (soil is brown, the sky
// blue, haze grey).
inline bool isGrassPixel(const cv::Vec3b& bgr) {
    return bgr[1] > bgr[2] + 8 && bgr[1] > bgr[0] + 8;
}

// Share of the pixels of `bgr` inside `area` (the whole image by default) that are grass.
inline double grassShare(const cv::Mat& bgr, cv::Rect area = {}) {
    if (area.area() == 0) area = cv::Rect(0, 0, bgr.cols, bgr.rows);
    int grass = 0;
    for (int y = area.y; y < area.y + area.height; ++y)
        for (int x = area.x; x < area.x + area.width; ++x)
            grass += isGrassPixel(bgr.at<cv::Vec3b>(y, x));
    return static_cast<double>(grass) / static_cast<double>(area.area());
}

}  // namespace meadow::test
