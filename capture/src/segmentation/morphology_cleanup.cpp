// Morphological clean-up of the foreground mask: closing bridges one-pixel dropouts along thin
// blades, the edge is smoothed along the contour (contour_smoothing.cpp), small regions are
// speckle, small enclosed holes are missing readings, and thin fragments are joined to what lies
// past their ends (fragment_links.cpp). Larger holes are kept: a loop enclosed
// by blades means blades cross (flagged in contour_extraction.cpp).
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

cv::Rect cleanUpRegion(const cv::Mat1b& mask, const SegmenterParams& params) {
    const cv::Rect box = cv::boundingRect(mask);
    if (box.empty()) return box;
    // Closing and opening reach their kernel's radius each way; edge smoothing moves the edge
    // out by at most its shift and half a pixel; one more pixel keeps a background ring around
    // everything.
    const int reach_px = params.closeKernel_px / 2 + params.openKernel_px / 2 +
                         static_cast<int>(std::ceil(params.edgeSmoothingMaxShift_px + 0.5f)) + 1;
    return grownWithin(box, reach_px, cv::Rect(0, 0, mask.cols, mask.rows));
}

void cleanUpMask(const SegmenterParams& params, cv::Mat1b& mask, StageReport& report) {
    if (params.closeKernel_px > 1) {
        const cv::Mat k = cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                                    {params.closeKernel_px, params.closeKernel_px});
        cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, k);
    }
    if (params.openKernel_px > 1) {
        const cv::Mat k = cv::getStructuringElement(cv::MORPH_ELLIPSE,
                                                    {params.openKernel_px, params.openKernel_px});
        const int before = cv::countNonZero(mask);
        cv::morphologyEx(mask, mask, cv::MORPH_OPEN, k);
        report.notes.push_back("opening dropped " +
                               std::to_string(before - cv::countNonZero(mask)) + " px");
    }
    smoothContours(mask, params.edgeSmoothingSigma_px, params.edgeSmoothingMaxShift_px, report);
    // Small regions.
    cv::Mat1i labels;
    cv::Mat stats, centroids;
    const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
    std::vector<char> drop(static_cast<size_t>(n), 0);
    int dropRegions = 0, dropPixels = 0;
    for (int i = 1; i < n; ++i)
        if (stats.at<int>(i, cv::CC_STAT_AREA) < params.minRegionArea_px) {
            drop[static_cast<size_t>(i)] = 1;
            ++dropRegions;
            dropPixels += stats.at<int>(i, cv::CC_STAT_AREA);
        }
    if (dropRegions > 0) {
        for (int y = 0; y < mask.rows; ++y) {
            auto* m = mask[y];
            const auto* l = labels[y];
            for (int x = 0; x < mask.cols; ++x)
                if (drop[static_cast<size_t>(l[x])]) m[x] = 0;
        }
        report.notes.push_back("dropped " + std::to_string(dropRegions) +
                               " region(s) smaller than " +
                               std::to_string(params.minRegionArea_px) + " px (" +
                               std::to_string(dropPixels) + " px): speckle");
    }
    // Thin fragments joined to what lies past their ends, before the holes: a link may close one.
    linkFragments(params, labels, stats, drop, mask, report);
    // Small holes: background components (4-connected) that do not touch the border.
    if (params.maxHoleArea_px > 0) {
        const cv::Mat1b background = mask == 0;
        const int nb =
            cv::connectedComponentsWithStats(background, labels, stats, centroids, 4, CV_32S);
        int filled = 0, filledPixels = 0, kept = 0;
        std::vector<char> fill(static_cast<size_t>(nb), 0);
        for (int i = 1; i < nb; ++i) {
            const int x = stats.at<int>(i, cv::CC_STAT_LEFT), y = stats.at<int>(i, cv::CC_STAT_TOP);
            const int w = stats.at<int>(i, cv::CC_STAT_WIDTH),
                      h = stats.at<int>(i, cv::CC_STAT_HEIGHT);
            const bool border = x == 0 || y == 0 || x + w == mask.cols || y + h == mask.rows;
            if (border) continue;
            if (stats.at<int>(i, cv::CC_STAT_AREA) <= params.maxHoleArea_px) {
                fill[static_cast<size_t>(i)] = 1;
                ++filled;
                filledPixels += stats.at<int>(i, cv::CC_STAT_AREA);
            } else {
                ++kept;
            }
        }
        if (filled > 0) {
            for (int y = 0; y < mask.rows; ++y) {
                auto* m = mask[y];
                const auto* l = labels[y];
                for (int x = 0; x < mask.cols; ++x)
                    if (fill[static_cast<size_t>(l[x])]) m[x] = 255;
            }
            report.notes.push_back("filled " + std::to_string(filled) + " hole(s) up to " +
                                   std::to_string(params.maxHoleArea_px) + " px (" +
                                   std::to_string(filledPixels) + " px): missing readings");
        }
        if (kept > 0)
            report.notes.push_back("kept " + std::to_string(kept) +
                                   " enclosed hole(s) larger than " +
                                   std::to_string(params.maxHoleArea_px) +
                                   " px: blades enclosing a gap (crossing blades)");
    }
}

}  // namespace meadow::capture::segmentation
