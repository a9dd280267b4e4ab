// How thick an object's parts are, and whether that is thin enough for leaves: what tells a
// plant from furniture, a wall's remnant or a person whichever way the plant was found.
#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {
// Holes in a surface's readings (dark spots, depth jumps) up to this across are filled before
// its parts are measured: a depth slice of a solid object is riddled with them. The gaps
// between leaves stay open: they are open to the outside.
constexpr float kMaxHole_m = 0.03f;
// A pot's wall is wider than a leaf: an opening with a disc of this diameter keeps the pot and
// the soil, not the leaves. Wider leaves than this seen face-on survive it too, but only the part
// that holds the plant's lowest row is taken for the pot.
constexpr float kPotMinWidth_m = 0.035f;
constexpr float kPotHeightOverWidth = 1.3f;
// What is left of an object once its thick base is off must hold this share of it to be
// measured as its parts; less, and the object is all thick.
constexpr double kMinPartsShare = 0.1;
}  // namespace

cv::Mat1b thickBase(const cv::Mat1b& mask, float depth_m, const Intrinsics& k) {
    const int diameter_px =
        std::max(3, static_cast<int>(std::lround(kPotMinWidth_m * k.fx_px / depth_m)));
    cv::Mat1b pot = cv::Mat1b::zeros(mask.size());
    const cv::Rect box = cv::boundingRect(mask);
    if (box.empty()) return pot;
    const cv::Rect around = grownWithin(box, diameter_px, cv::Rect({0, 0}, mask.size()));
    const cv::Mat1b part = mask(around);
    cv::Mat1b thick;
    cv::morphologyEx(part, thick, cv::MORPH_OPEN,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, {diameter_px, diameter_px}));
    if (cv::countNonZero(thick) == 0) return pot;
    const int lowest = box.y + box.height - 1 - around.y;
    cv::Mat1i labels;
    cv::Mat stats, centroids;
    const int n = cv::connectedComponentsWithStats(thick, labels, stats, centroids, 8);
    cv::Mat1b potPart = pot(around);
    for (int i = 1; i < n; ++i) {
        const int top = stats.at<int>(i, cv::CC_STAT_TOP);
        const int bottom = top + stats.at<int>(i, cv::CC_STAT_HEIGHT) - 1;
        if (bottom < lowest - diameter_px / 2) continue;
        // A pot is about as tall as it is wide: the thick part is cleared from its bottom up to
        // kPotHeightOverWidth times its width there, not where thick leaves join it above.
        int width_px = 0;  // its widest row near its bottom (a pot's bottom row is a rim)
        for (int y = std::max(top, bottom - diameter_px); y <= bottom; ++y) {
            int row = 0;
            for (int x = 0; x < labels.cols; ++x) row += labels(y, x) == i;
            width_px = std::max(width_px, row);
        }
        const int from = std::max(top, bottom - static_cast<int>(kPotHeightOverWidth * width_px));
        for (int y = from; y <= bottom; ++y)
            for (int x = 0; x < labels.cols; ++x)
                if (labels(y, x) == i) potPart(y, x) = 255;
    }
    if (cv::countNonZero(potPart) == 0) return pot;
    cv::dilate(potPart, potPart, cv::getStructuringElement(cv::MORPH_ELLIPSE, {5, 5}));
    potPart &= part;
    return pot;
}

PartShape partShape(const cv::Mat1b& mask, float depth_m, const Intrinsics& k, bool fillHoles,
                    const cv::Mat1b& cutFrom) {
    const cv::Mat1b& whole = cutFrom.empty() ? mask : cutFrom;
    const cv::Rect box = grownWithin(cv::boundingRect(whole), 1, cv::Rect({0, 0}, mask.size()));
    if (box.empty()) return {};
    const auto closedOf = [&](const cv::Mat1b& m) {
        cv::Mat1b closed = m(box).clone();
        if (!fillHoles) return closed;
        const double maxHole_px = kMaxHole_m * k.fx_px / depth_m;
        std::vector<std::vector<cv::Point>> contours;
        std::vector<cv::Vec4i> hierarchy;
        cv::findContours(closed.clone(), contours, hierarchy, cv::RETR_CCOMP,
                         cv::CHAIN_APPROX_SIMPLE);
        for (std::size_t i = 0; i < contours.size(); ++i)
            if (hierarchy[i][3] >= 0 && cv::contourArea(contours[i]) <= maxHole_px * maxHole_px)
                cv::drawContours(closed, contours, static_cast<int>(i), 255, cv::FILLED);
        return closed;
    };
    const cv::Mat1b counted = closedOf(mask);
    cv::Mat1f distance;
    cv::distanceTransform(cutFrom.empty() ? counted : closedOf(cutFrom) | counted, distance,
                          cv::DIST_L2, cv::DIST_MASK_PRECISE);
    std::vector<float> d;
    for (int y = 0; y < distance.rows; ++y)
        for (int x = 0; x < distance.cols; ++x)
            if (counted(y, x)) d.push_back(distance(y, x));
    if (d.empty()) return {};
    std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
    // A strip W wide has its pixels' distances to the edge spread evenly over [0, W/2]: the
    // median doubled is W/2, and its length is its area over W. The distance transform measures
    // to the centre of the nearest pixel outside, half a pixel past the edge.
    const float width_px = 2.f * std::max(d[d.size() / 2] - 0.5f, 0.5f);
    // Each piece's length over that width, weighted by its area: a plant's leaves, joined or
    // apart, are each long; a tray of round heads or a heap of cushions is many short pieces
    // whose lengths would add up to a long one.
    cv::Mat1i labels;
    cv::Mat stats, centroids;
    const int n = cv::connectedComponentsWithStats(counted, labels, stats, centroids, 8);
    double area = 0.0, areaSquared = 0.0;
    for (int i = 1; i < n; ++i) {
        const double a = stats.at<int>(i, cv::CC_STAT_AREA);
        area += a;
        areaSquared += a * a;
    }
    PartShape shape;
    shape.width_m = width_px * depth_m / k.fx_px;
    shape.elongation =
        static_cast<float>(areaSquared / std::max(area, 1.0)) / (4.f * width_px * width_px);
    return shape;
}

std::string unlikeLeafParts(const PartShape& shape, const SegmenterParams& params) {
    std::ostringstream why;
    why.precision(2);
    // A grown maize shoot's leaves (7-13 cm across) seen face-on measure wider than a grass's,
    // up to half as wide again as the limit; so do a board's or a table top's. Its leaves are
    // many and long: its parts, by area, are far longer over their width than furniture's.
    const float broadMaxWidth_m = kBroadLeafWidthShare * params.plantMaxMeanWidth_m;
    const bool broad = shape.width_m <= broadMaxWidth_m;
    if (shape.width_m > params.plantMaxMeanWidth_m &&
        !(broad && shape.elongation >= kBroadLeafMinElongation)) {
        why << "made of parts " << shape.width_m * 100 << " cm wide";
        if (broad) why << " and " << shape.elongation << " times as long";
        why << " (leaves: under " << params.plantMaxMeanWidth_m * 100 << " cm, or "
            << broadMaxWidth_m * 100 << " cm when " << kBroadLeafMinElongation << " times as long)";
    } else if (shape.elongation < kMinLeafElongation)
        why << shape.elongation << " times as long as it is wide (leaves: over "
            << kMinLeafElongation << ")";
    return why.str();
}

std::string unlikeLeaves(const cv::Mat1b& mask, const cv::Mat1w& depth_mm, const Intrinsics& k,
                         const SegmenterParams& params) {
    std::vector<std::uint16_t> depths;
    const cv::Rect box = cv::boundingRect(mask);
    for (int y = box.y; y < box.y + box.height; ++y)
        for (int x = box.x; x < box.x + box.width; ++x)
            if (mask(y, x) && depth_mm(y, x) > 0) depths.push_back(depth_mm(y, x));
    if (depths.empty()) return {};
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    const float depth_m = depths[depths.size() / 2] / kMillimetresPerMetre;
    // A young plant's pot may stand nearest: its leaves are what grows out of it.
    const cv::Mat1b parts = mask & ~thickBase(mask, depth_m, k);
    const int partsArea = cv::countNonZero(parts);
    if (partsArea < kMinPartsShare * static_cast<double>(cv::countNonZero(mask)))
        return "thick throughout (a pot, a box or furniture; no leaves grow out of it)";
    // The parts are measured within the whole object: where they were cut from its base is no
    // edge (the top of a box taller than a pot is as thick as the box, not a strip).
    return unlikeLeafParts(partShape(parts, depth_m, k, true, mask), params);
}

}  // namespace meadow::capture::segmentation
