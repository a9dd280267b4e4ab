// Contours and the cluster reference point (Fan & Sheng 2017, Sec. 4.2). The paper measures the
// contour's distance from the cluster centre; for a tuft seen from the side the blades meet at
// the base, so the lowest part of the cluster (the base point) puts the distance minima where
// the blades actually part. Both are computed; params.reference picks the one used.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {
// A centre deeper inside the cluster than this share of its farthest contour point means the
// blades radiate around it: the camera looks down on the tuft and the base is hidden.
constexpr float kRadialDepthFraction = 0.3f;
}  // namespace

std::vector<BladeCluster> extractClusters(const cv::Mat1b& mask, const cv::Rect& region,
                                          const SensedExtent& sensed, const SegmenterParams& params,
                                          StageReport& report) {
    std::vector<std::vector<cv::Point>> contours;
    std::vector<cv::Vec4i> hierarchy;
    if (!region.empty())
        cv::findContours(mask(region).clone(), contours, hierarchy, cv::RETR_CCOMP,
                         cv::CHAIN_APPROX_NONE, region.tl());
    std::vector<BladeCluster> clusters;
    int tooSmall = 0;
    for (size_t i = 0; i < contours.size(); ++i) {
        if (hierarchy[i][3] >= 0) continue;  // a hole; handled with its parent
        auto& contour = contours[i];
        const cv::Rect box = cv::boundingRect(contour);
        cv::Mat1b region(box.size(), std::uint8_t{0});
        cv::drawContours(region, contours, static_cast<int>(i), 255, cv::FILLED, cv::LINE_8,
                         cv::noArray(), 0, -box.tl());
        region &= mask(box);
        const int area = cv::countNonZero(region);
        if (area < std::max(1, params.minRegionArea_px) || contour.size() < 3) {
            ++tooSmall;
            continue;
        }
        BladeCluster c;
        // One orientation for every cluster: counter-clockwise as seen on screen (y down).
        if (cv::contourArea(contour, /*oriented=*/true) > 0)
            std::reverse(contour.begin(), contour.end());
        c.contour_px = contour;
        c.area_px = area;
        const cv::Moments m = cv::moments(region, /*binaryImage=*/true);
        c.centre_px = {static_cast<float>(m.m10 / m.m00) + static_cast<float>(box.x),
                       static_cast<float>(m.m01 / m.m00) + static_cast<float>(box.y)};
        // Base point: centroid of the region's lowest rows.
        const int bandRows = std::max(
            1,
            static_cast<int>(std::round(params.baseBandFraction * static_cast<float>(box.height))));
        double sx = 0, sy = 0, n = 0;
        for (int y = box.height - bandRows; y < box.height; ++y)
            for (int x = 0; x < box.width; ++x)
                if (region(y, x)) {
                    sx += x;
                    sy += y;
                    n += 1;
                }
        c.basePoint_px = n > 0 ? cv::Point2f(static_cast<float>(sx / n) + static_cast<float>(box.x),
                                             static_cast<float>(sy / n) + static_cast<float>(box.y))
                               : cv::Point2f(c.centre_px.x, static_cast<float>(box.br().y - 1));
        c.reference_px =
            params.reference == ReferencePoint::BasePoint ? c.basePoint_px : c.centre_px;

        // Holes larger than the clean-up fills: blades cross and enclose a gap.
        int holes = 0;
        for (int h = hierarchy[i][2]; h >= 0; h = hierarchy[static_cast<size_t>(h)][0]) ++holes;
        if (holes > 0)
            addFlag(
                c, BladeFlag::Overlapping,
                "the cluster encloses " + std::to_string(holes) +
                    " hole(s) larger than maxHoleArea_px: blades cross, cuts there may be wrong");
        // The bottom of what was sensed: the image border, or the band of no readings a
        // structured-light camera leaves along it.
        if (std::any_of(contour.begin(), contour.end(),
                        [&](const cv::Point& p) { return sensed.atBottom(p); }))
            addFlag(c, BladeFlag::BaseHidden,
                    "the cluster reaches the bottom of what the sensor read (image border or its "
                    "band of no readings): its base may lie below it");
        const cv::Point centre(cvRound(c.centre_px.x), cvRound(c.centre_px.y));
        if (cv::Rect(0, 0, mask.cols, mask.rows).contains(centre) && mask(centre)) {
            const double inside = cv::pointPolygonTest(contour, c.centre_px, /*measureDist=*/true);
            double farthest = 0;
            for (const auto& p : contour)
                farthest = std::max(farthest, cv::norm(cv::Point2f(p) - c.centre_px));
            if (inside > kRadialDepthFraction * farthest)
                addFlag(c, BladeFlag::BaseHidden,
                        "the blades radiate around the cluster centre: the camera looks down on "
                        "the tuft and the base is hidden; view it from the side");
        }
        clusters.push_back(std::move(c));
    }
    if (tooSmall > 0)
        report.notes.push_back(std::to_string(tooSmall) +
                               " contour(s) smaller than minRegionArea_px");
    report.notes.push_back(std::to_string(clusters.size()) + " cluster(s); reference " +
                           toString(params.reference));
    return clusters;
}

cv::Mat1b clusterRegion(const BladeCluster& cluster, const cv::Mat1b& mask, cv::Rect& box) {
    box = cv::boundingRect(cluster.contour_px);
    cv::Mat1b region(box.size(), std::uint8_t{0});
    cv::drawContours(region, std::vector<std::vector<cv::Point>>{cluster.contour_px}, 0, 255,
                     cv::FILLED, cv::LINE_8, cv::noArray(), 0, -box.tl());
    region &= mask(box);
    return region;
}

}  // namespace meadow::capture::segmentation
