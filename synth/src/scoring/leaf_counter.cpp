#include "meadow/synth/leaf_counter.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>
#include <vector>

namespace meadow::synth {
namespace {

constexpr float kMiddleShare = 0.5f;  // the plant's region is the band's largest in the middle half

}  // namespace

int countLeavesPlainly(const cv::Mat1w& depth, float near_m, float far_m) {
    const cv::Rect centre(static_cast<int>(depth.cols * (0.5f - 0.5f * kMiddleShare)),
                          static_cast<int>(depth.rows * (0.5f - 0.5f * kMiddleShare)),
                          static_cast<int>(depth.cols * kMiddleShare),
                          static_cast<int>(depth.rows * kMiddleShare));
    cv::Mat1b band;
    cv::inRange(depth, std::max(1, static_cast<int>(near_m * 1000.f)),
                static_cast<int>(far_m * 1000.f), band);
    cv::morphologyEx(band, band, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
    cv::morphologyEx(band, band, cv::MORPH_CLOSE,
                     cv::getStructuringElement(cv::MORPH_RECT, {5, 5}));
    cv::Mat1i components;
    const int n = cv::connectedComponents(band, components, 8, CV_32S);
    std::vector<int> inCentre(static_cast<std::size_t>(n), 0);
    for (int y = centre.y; y < centre.br().y; ++y)
        for (int x = centre.x; x < centre.br().x; ++x)
            ++inCentre[static_cast<std::size_t>(components(y, x))];
    inCentre[0] = 0;
    const int plant =
        static_cast<int>(std::max_element(inCentre.begin(), inCentre.end()) - inCentre.begin());
    if (plant == 0) return 0;
    const cv::Mat1b region = components == plant;
    cv::Mat1b skeleton;
    cv::ximgproc::thinning(region, skeleton, cv::ximgproc::THINNING_ZHANGSUEN);
    int ends = 0;
    for (int y = 1; y + 1 < skeleton.rows; ++y)
        for (int x = 1; x + 1 < skeleton.cols; ++x) {
            if (!skeleton(y, x)) continue;
            int neighbours = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    neighbours += (dx || dy) && skeleton(y + dy, x + dx);
            ends += neighbours == 1;
        }
    return std::max(0, ends - 1);
}

}  // namespace meadow::synth
