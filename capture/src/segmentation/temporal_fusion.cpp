// Temporal fusion of a still tuft: per-pixel median of the valid readings. The median rejects
// flying pixels and single-frame dropouts that a mean would smear into the result.
#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

cv::Mat1w fuseFrames(std::span<const DepthFrame> frames, float minValidFrameFraction,
                     StageReport& report) {
    const cv::Size size = frames[0].depth_mm.size();
    const int needed = std::max(
        1, static_cast<int>(std::ceil(minValidFrameFraction * static_cast<float>(frames.size()))));
    cv::Mat1w fused(size, 0);
    std::vector<std::uint16_t> values;
    values.reserve(frames.size());
    int tooFew = 0;
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            values.clear();
            for (const auto& f : frames)
                if (const auto d = f.depth_mm(y, x); d != 0) values.push_back(d);
            if (values.empty()) continue;
            if (static_cast<int>(values.size()) < needed) {
                ++tooFew;
                continue;
            }
            const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
            std::nth_element(values.begin(), mid, values.end());
            fused(y, x) = *mid;
        }
    report.droppedPixels = tooFew;
    report.keptPixels = cv::countNonZero(fused);
    report.notes.push_back("median of " + std::to_string(frames.size()) + " frames; " +
                           std::to_string(tooFew) + " px dropped: valid in fewer than " +
                           std::to_string(needed) + " frames");
    return fused;
}

}  // namespace meadow::capture::segmentation
