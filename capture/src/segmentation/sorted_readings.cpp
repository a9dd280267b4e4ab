// Frames sorted per pixel (sorted_readings.h), and the nearest run of agreeing readings in them.
#include "segmentation/sorted_readings.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

namespace meadow::capture::segmentation {

int framesForShare(float share, std::size_t frames, int atLeast) {
    return std::max(atLeast, static_cast<int>(std::ceil(share * static_cast<float>(frames))));
}

std::vector<cv::Mat1w> sortedReadings(std::span<const DepthFrame> frames) {
    const std::size_t n = frames.size();
    // cv::Mat while sorting, not Mat1w: std::min would take a Mat1w for a comparator.
    std::vector<cv::Mat> sorted(n);
    for (std::size_t i = 0; i < n; ++i) {
        sorted[i] = frames[i].depth_mm.clone();
        sorted[i].setTo(kNoReading, frames[i].depth_mm == 0);
    }
    cv::Mat low, high;
    const auto exchange = [&](std::size_t a, std::size_t b) {
        cv::min(sorted[a], sorted[b], low);
        cv::max(sorted[a], sorted[b], high);
        std::swap(sorted[a], low);
        std::swap(sorted[b], high);
    };
    std::size_t padded = 1;
    while (padded < n) padded <<= 1;
    // Comparators that touch the padding (no reading, already last) change nothing: skipped.
    for (std::size_t p = 1; p < padded; p <<= 1)
        for (std::size_t k = p; k >= 1; k >>= 1)
            for (std::size_t j = k % p; j + k < padded; j += 2 * k)
                for (std::size_t i = 0; i < std::min(k, padded - j - k); ++i)
                    if ((i + j) / (2 * p) == (i + j + k) / (2 * p) && i + j + k < n)
                        exchange(i + j, i + j + k);
    return {sorted.begin(), sorted.end()};
}

cv::Mat1w nearestRecurring(const std::vector<cv::Mat1w>& sorted, int needed, int agreement_mm) {
    cv::Mat1w out(sorted.front().size(), std::uint16_t{0});
    const auto n = sorted.size(), run = static_cast<std::size_t>(needed);
    if (run < 1 || run > n) return out;
    // The nearest run of `needed` readings that agree: a tip in front of the wall is the nearer
    // surface, and the wall's readings agree with one another too. Runs are tried farthest first
    // so that the nearest one that agrees is written last.
    cv::Mat spread;
    cv::Mat1b agree, read;
    for (std::size_t i = n - run + 1; i-- > 0;) {
        const cv::Mat1w& last = sorted[i + run - 1];
        cv::subtract(last, sorted[i], spread);
        cv::compare(spread, agreement_mm, agree, cv::CMP_LE);
        cv::compare(last, kNoReading, read, cv::CMP_NE);
        agree &= read;
        sorted[i + (run - 1) / 2].copyTo(out, agree);
    }
    return out;
}

}  // namespace meadow::capture::segmentation
