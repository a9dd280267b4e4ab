// Flags with reasons: what the segmentation cannot vouch for. Nothing is silently dropped or
// silently trusted; each flag carries one human-readable line.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "segmentation/polyline.h"
#include "segmentation/stages.h"

namespace meadow::capture {

namespace segmentation {

namespace {
constexpr int kSpineSamples =
    8;  // centre-line samples for the curl test (few: noise must not add turns)
constexpr float kRadToDeg = 180.0f / std::numbers::pi_v<float>;
constexpr int kHoleNeighbourhood_px = 2;  // a blade this close to an enclosed gap crosses it
constexpr size_t kMinBladesForWidthMedian = 3;

std::string fixed(double v, int digits = 1) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(digits);
    s << v;
    return s.str();
}

// Centre line: side A (start -> tip) and side B (end -> tip) resampled and averaged.
std::vector<cv::Point2f> centreLine(const BladeContour& blade) {
    const auto& c = blade.contour_px;
    if (c.size() < 4 || blade.tipIndex <= 0 || blade.tipIndex >= static_cast<int>(c.size()) - 1)
        return {};
    std::vector<cv::Point2f> a(c.begin(), c.begin() + blade.tipIndex + 1);
    std::vector<cv::Point2f> b(c.rbegin(),
                               c.rbegin() + static_cast<std::ptrdiff_t>(c.size()) - blade.tipIndex);
    const auto ra = resampledEvenly(a, kSpineSamples), rb = resampledEvenly(b, kSpineSamples);
    std::vector<cv::Point2f> mid(static_cast<size_t>(kSpineSamples));
    for (size_t i = 0; i < mid.size(); ++i) mid[i] = 0.5f * (ra[i] + rb[i]);
    return mid;
}

// Pixels of `mask` whose eight neighbours are all set (what a 3x3 erosion keeps, outside
// counting as unset). A loop: a dozen cv::erode calls on small masks cost more in overhead.
int interiorPixels(const cv::Mat1b& mask) {
    int count = 0;
    for (int y = 1; y + 1 < mask.rows; ++y) {
        const std::uint8_t* above = mask[y - 1];
        const std::uint8_t* row = mask[y];
        const std::uint8_t* below = mask[y + 1];
        for (int x = 1; x + 1 < mask.cols; ++x)
            count += above[x - 1] && above[x] && above[x + 1] && row[x - 1] && row[x] &&
                     row[x + 1] && below[x - 1] && below[x] && below[x + 1];
    }
    return count;
}

float totalTurn_deg(const std::vector<cv::Point2f>& line) {
    float turn = 0.f;
    for (size_t i = 2; i < line.size(); ++i) {
        const cv::Point2f u = line[i - 1] - line[i - 2], v = line[i] - line[i - 1];
        if (cv::norm(u) < 1e-3 || cv::norm(v) < 1e-3) continue;
        turn += std::abs(std::atan2(u.x * v.y - u.y * v.x, u.dot(v)));
    }
    return turn * kRadToDeg;
}
}  // namespace

void addFlag(BladeContour& blade, BladeFlag flag, std::string reason) {
    if (std::find(blade.flags.begin(), blade.flags.end(), flag) != blade.flags.end()) return;
    blade.flags.push_back(flag);
    blade.reasons.push_back(toString(flag) + ": " + std::move(reason));
}
void addFlag(BladeCluster& cluster, BladeFlag flag, std::string reason) {
    cluster.flags.push_back(flag);
    cluster.reasons.push_back(toString(flag) + ": " + std::move(reason));
}

void flagBlades(std::span<BladeContour> blades, const BladeCluster& cluster, cv::Size frameSize,
                const SensedExtent& sensed, const SegmenterParams& params, float raggedness) {
    std::vector<float> widths;
    // Enclosed gaps of the cluster (holes the clean-up kept): the blades around them cross.
    cv::Mat1b holes(frameSize, std::uint8_t{0});
    // Not for the stem partition: it follows leaves through the crossings that close such gaps,
    // and flags itself the leaves it could not follow (stem_partition.cpp).
    const bool hasHoles = params.partition != PartitionMethod::StemGraph &&
                          std::find(cluster.flags.begin(), cluster.flags.end(),
                                    BladeFlag::Overlapping) != cluster.flags.end();
    if (hasHoles) {
        cv::drawContours(holes, std::vector<std::vector<cv::Point>>{cluster.contour_px}, 0, 255,
                         cv::FILLED);
        cv::Mat1b any(frameSize, std::uint8_t{0});
        for (const auto& b : blades) {
            cv::Mat1b under = any(b.maskBox_px());
            under |= b.mask;
        }
        holes &= ~any;
        cv::dilate(holes, holes, cv::Mat(), {-1, -1}, kHoleNeighbourhood_px);
    }
    for (auto& blade : blades) {
        // Truncated: the contour runs along the image border, or along the band by a border
        // where the sensor read nothing.
        const auto onBorder = std::count_if(blade.contour_px.begin(), blade.contour_px.end(),
                                            [&](cv::Point p) { return sensed.atEdge(p); });
        if (onBorder > 0)
            addFlag(blade, BladeFlag::Truncated,
                    std::to_string(onBorder) +
                        " contour px on the image border or on the sensor's band of no readings "
                        "along it: the blade may continue where nothing was sensed");
        // Width = area / centre-line length.
        const auto mid = centreLine(blade);
        double length = 0.0;
        for (size_t i = 1; i < mid.size(); ++i) length += cv::norm(mid[i] - mid[i - 1]);
        const double area = cv::countNonZero(blade.mask);
        const double width = length > 0.0 ? area / length : 0.0;
        widths.push_back(static_cast<float>(width));
        if (width < params.minResolvableWidth_px) {
            addFlag(blade, BladeFlag::TooThin,
                    "mean width " + fixed(width) + " px < " + fixed(params.minResolvableWidth_px) +
                        " px: narrower than the sensor resolves; widths are unreliable");
        } else if (params.minInteriorFraction > 0.f && raggedness >= params.raggedEdges &&
                   area > 0.0) {
            const double share = interiorPixels(blade.mask) / area;
            if (share < params.minInteriorFraction)
                addFlag(blade, BladeFlag::TooThin,
                        "only " + fixed(100.0 * share, 0) +
                            " % of its pixels lie over a pixel inside its edge (needs " +
                            fixed(100.0 * params.minInteriorFraction, 0) +
                            " %): under ~3 px wide, where the sensor's lateral noise is a third "
                            "of the width; its edges and widths are unreliable");
        }
        const float turn = totalTurn_deg(mid);
        if (turn > params.curlTurn_deg) {
            const float miss = quadraticBezierMiss_px(mid);
            if (miss > params.curlMissShare * length)
                addFlag(blade, BladeFlag::CurlsSideways,
                        "centre line turns " + fixed(turn, 0) + " deg (> " +
                            fixed(params.curlTurn_deg, 0) +
                            ") and a quadratic spine misses it by " + fixed(miss, 1) + " px (" +
                            fixed(100.0 * miss / length, 0) + " % of its length, > " +
                            fixed(100.0 * params.curlMissShare, 0) +
                            " %): the blade curls or folds; the symmetric match may pair wrong "
                            "points");
        }
        if (hasHoles && cv::countNonZero(blade.mask & holes(blade.maskBox_px())) > 0)
            addFlag(blade, BladeFlag::Overlapping,
                    "the blade borders a gap enclosed by blades: it crosses another blade");
        for (size_t k = 0; k < cluster.flags.size(); ++k)
            if (cluster.flags[k] == BladeFlag::BaseHidden)
                addFlag(blade, BladeFlag::BaseHidden, "its cluster's " + cluster.reasons[k]);
    }
    if (blades.size() >= kMinBladesForWidthMedian) {
        std::vector<float> sorted = widths;
        std::nth_element(sorted.begin(),
                         sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2),
                         sorted.end());
        const float median = sorted[sorted.size() / 2];
        for (size_t i = 0; i < blades.size(); ++i)
            if (median > 0.f && widths[i] > params.overlapWidthRatio * median)
                addFlag(blades[i], BladeFlag::Overlapping,
                        "mean width " + fixed(widths[i]) + " px is " + fixed(widths[i] / median) +
                            "x the cluster's median: probably several blades the contour could not "
                            "part");
    }
}

}  // namespace segmentation
}  // namespace meadow::capture
