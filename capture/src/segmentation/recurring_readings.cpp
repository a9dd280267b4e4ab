// Recurring readings (recurring_readings.h): per pixel, the nearest depth that enough frames
// read within a few millimetres of one another.
#include "meadow/capture/recurring_readings.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "meadow/capture/error.h"
#include "segmentation/sorted_readings.h"

namespace meadow::capture {

namespace {
constexpr int kMaxAgreement_mm = 1000;
}  // namespace

std::string RecurringParams::problem() const {
    if (!std::isfinite(minShare) || minShare < 0.f || minShare > 1.f)
        return "RecurringParams::minShare must be in [0, 1], got " + std::to_string(minShare);
    if (minFrames < 1)
        return "RecurringParams::minFrames must be >= 1, got " + std::to_string(minFrames);
    if (agreement_mm < 0 || agreement_mm > kMaxAgreement_mm)
        return "RecurringParams::agreement_mm must be in [0, " + std::to_string(kMaxAgreement_mm) +
               "], got " + std::to_string(agreement_mm);
    return {};
}

RecurringReadings recurringReadings(std::span<const DepthFrame> frames,
                                    const RecurringParams& params) {
    if (const std::string why = params.problem(); !why.empty())
        throw CaptureError(why + "; fix the recurring-readings parameters");
    if (frames.empty()) throw CaptureError("recurringReadings: no frames given");
    const cv::Size size = frames.front().depth_mm.size();
    for (const DepthFrame& f : frames)
        if (f.depth_mm.size() != size)
            throw CaptureError("recurringReadings: frame " + std::to_string(f.index) +
                               " differs in size from frame " +
                               std::to_string(frames.front().index) +
                               "; recurring readings need frames of one camera");
    RecurringReadings out;
    out.frames = static_cast<int>(frames.size());
    out.neededFrames =
        std::max(params.minFrames,
                 static_cast<int>(std::ceil(params.minShare * static_cast<float>(out.frames))));
    if (static_cast<std::size_t>(out.neededFrames) > frames.size()) {
        out.depth_mm = cv::Mat1w(size, std::uint16_t{0});  // too few frames for anything to recur
        return out;
    }
    out.depth_mm = segmentation::nearestRecurring(segmentation::sortedReadings(frames),
                                                  out.neededFrames, params.agreement_mm);
    out.recurringPixels = cv::countNonZero(out.depth_mm);
    return out;
}

}  // namespace meadow::capture

namespace meadow::capture::segmentation {

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
