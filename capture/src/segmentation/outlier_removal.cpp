// Outlier removal: flying pixels between a blade and the background, and isolated speckle.
//  - OrganizedNeighbourhood: a pixel stays when at least outlierMinNeighbours pixels of its
//    outlierWindow_px window are masked and within outlierDepthTolerance_m of its depth. It uses
//    the image grid as the neighbourhood, so it needs no k-d tree.
//  - Statistical: pcl::StatisticalOutlierRemoval (mean distance to the k nearest neighbours
//    beyond mean + stddevMul x sigma) on the masked points, with a k-d tree.
// One of the two files that include PCL (the other is plane_removal.cpp).
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {

int organizedNeighbourhood(const cv::Mat1w& depth_mm, const SegmenterParams& params,
                           cv::Mat1b& mask) {
    const int r = params.outlierWindow_px / 2;
    const int tol_mm = static_cast<int>(params.outlierDepthTolerance_m * kMillimetresPerMetre);
    const int needed = params.outlierMinNeighbours + 1;  // +1: the pixel counts itself
    // Only the masked part of the frame can change; the window reads r px around it.
    const cv::Rect box = cv::boundingRect(mask);
    if (box.empty()) return 0;
    const cv::Rect window = grownWithin(box, r, cv::Rect(0, 0, mask.cols, mask.rows));
    const cv::Mat1b in = mask(window).clone();
    const cv::Mat1w depth = depth_mm(window);
    int dropped = 0;
    for (int y = 0; y < in.rows; ++y) {
        const auto* m = in[y];
        for (int x = 0; x < in.cols; ++x) {
            if (m[x] == 0) continue;
            const int d0 = depth(y, x);
            if (d0 == 0) {  // masked without a reading (segmentMask input): nothing to test
                continue;
            }
            // Counting stops once the pixel has enough support: most pixels of a blade have it
            // within the first rows of the window.
            int near = 0;
            for (int yy = std::max(0, y - r); yy <= std::min(in.rows - 1, y + r) && near < needed;
                 ++yy) {
                const auto* mm = in[yy];
                const auto* dd = depth[yy];
                for (int xx = std::max(0, x - r); xx <= std::min(in.cols - 1, x + r); ++xx)
                    near += mm[xx] != 0 && std::abs(static_cast<int>(dd[xx]) - d0) <= tol_mm;
            }
            if (near < needed) {
                mask(y + window.y, x + window.x) = 0;
                ++dropped;
            }
        }
    }
    return dropped;
}

int statistical(const cv::Mat1w& depth_mm, const Intrinsics& K, const SegmenterParams& params,
                cv::Mat1b& mask) {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    std::vector<cv::Point> pixel;
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x)
            if (mask(y, x) != 0 && depth_mm(y, x) != 0) {
                const auto v =
                    K.backProject(static_cast<float>(x), static_cast<float>(y),
                                  static_cast<float>(depth_mm(y, x)) / kMillimetresPerMetre);
                cloud->push_back(pcl::PointXYZ(v.x, v.y, v.z));
                pixel.emplace_back(x, y);
            }
    if (cloud->size() <= static_cast<size_t>(params.statisticalMeanK)) return 0;
    pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
    sor.setInputCloud(cloud);
    sor.setMeanK(params.statisticalMeanK);
    sor.setStddevMulThresh(params.statisticalStddevMul);
    pcl::Indices kept;
    sor.filter(kept);
    std::vector<char> keep(pixel.size(), 0);
    for (const auto i : kept) keep[static_cast<size_t>(i)] = 1;
    int dropped = 0;
    for (size_t i = 0; i < pixel.size(); ++i)
        if (!keep[i]) {
            mask(pixel[i]) = 0;
            ++dropped;
        }
    return dropped;
}

}  // namespace

void removeOutliers(const cv::Mat1w& depth_mm, const Intrinsics& intrinsics,
                    const SegmenterParams& params, cv::Mat1b& mask, StageReport& report) {
    const int dropped = params.outlierMethod == OutlierMethod::Statistical
                            ? statistical(depth_mm, intrinsics, params, mask)
                            : organizedNeighbourhood(depth_mm, params, mask);
    report.droppedPixels = dropped;
    report.notes.push_back(toString(params.outlierMethod) + ": " + std::to_string(dropped) +
                           " px dropped as flying pixels / speckle");
}

}  // namespace meadow::capture::segmentation
