// Depth-band mask (Fan & Sheng 2017, Sec. 4.1): the tuft is the part of the frame inside a band
// of depths. The user may give the band; otherwise it is the nearest dominant mode of the depth
// histogram, widened to the histogram's valleys on both sides.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <sstream>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {
// Histogram smoothing half-width in bins: a [1 2 3 2 1] kernel, enough to merge the comb that
// disparity quantisation leaves in the histogram of a structured-light sensor.
constexpr int kSmoothHalfWidth_bins = 2;
constexpr float kMaxHistogramDepth_m = 12.0f;
// A depth mode present in more than this share of the image columns is scenery seen edge-on
// (ground, a wall), not a tuft, when it also reaches across the frame or lies in stripes across
// it. Coverage alone is not enough: a tuft seen from close up spans as many columns, but it
// stays off the side borders and fills a few percent of each row, while ground and wall stripes
// reach both borders or, where the ground ends inside the view (a ground disc seen beyond the
// tuft), fill a third of the rows they lie in and more.
constexpr float kSceneryColumnCoverage = 0.6f;
// How near each side border a mode's pixels must come to reach across the frame.
constexpr float kSceneryBorderMargin = 0.05f;
// A stripe: a row the mode fills across this share of the columns; the mode is scenery when this
// share of its pixels lie in stripes. A tuft's rows hold a few blades and lie in no stripe; the
// far edge of a ground disc does, though the blades at its depths share its mode.
constexpr float kStripeRowFill = 0.3f;
constexpr double kSceneryStripeShare = 0.1;
// Valleys above this share of the mode's peak are crossed (between blades of one tuft).
constexpr double kBandFloorFraction = 0.25;
// Points sampled per mode for the flatness test: a 3x3 covariance needs no more.
constexpr int kFlatnessSamples = 2000;

struct Flatness {
    float tilt_deg = 90.f;    // angle between the points' thinnest direction and vertical
    float thickness_m = 0.f;  // standard deviation along that direction
};

// Principal axes of the masked points within [lo_mm, hi_mm). Ground that a plane fit left (a
// fit to the narrow strip of ground a low sensor still reads is poorly constrained in pitch and
// roll; a few degrees leave a strip of near ground 10-25 mm off the plane) is a flat, level
// patch: its thinnest axis is vertical. A tuft seen from the side spreads up and across, so its
// thinnest axis faces the camera.
Flatness flatness(const cv::Mat1w& depth_mm, const cv::Mat1b& mask, const Intrinsics& K,
                  float lo_mm, float hi_mm, double inRange) {
    const int step = std::max(1, static_cast<int>(inRange / kFlatnessSamples));
    std::vector<cv::Vec3f> points;
    int seen = 0;
    for (int y = 0; y < depth_mm.rows; ++y) {
        const auto* d = depth_mm[y];
        const auto* m = mask[y];
        for (int x = 0; x < depth_mm.cols; ++x) {
            if (!m[x] || d[x] == 0 || static_cast<float>(d[x]) < lo_mm ||
                static_cast<float>(d[x]) >= hi_mm || seen++ % step != 0)
                continue;
            const auto p = K.backProject(static_cast<float>(x), static_cast<float>(y),
                                         static_cast<float>(d[x]) / kMillimetresPerMetre);
            points.emplace_back(p.x, p.y, p.z);
        }
    }
    Flatness f;
    if (points.size() < 3) return f;
    const cv::PCA pca(cv::Mat(points).reshape(1), cv::noArray(), cv::PCA::DATA_AS_ROW);
    const float normalY = std::abs(pca.eigenvectors.at<float>(2, 1));
    f.tilt_deg = std::acos(std::min(1.f, normalY)) * 180.f / static_cast<float>(CV_PI);
    f.thickness_m = std::sqrt(std::max(0.f, pca.eigenvalues.at<float>(2)));
    return f;
}

std::string metres(float v) {
    std::ostringstream s;
    s.precision(3);
    s << v << " m";
    return s.str();
}

// The masked readings' depth histogram, and which image columns each bin's pixels fall in.
struct DepthHistogram {
    float bin_mm = 0.f;
    std::vector<double> count;
    std::size_t columns = 0;
    std::vector<std::uint8_t> columnHit;  // bins x columns, 1 where the bin has a pixel
    double total = 0.0;

    [[nodiscard]] int binOf(std::uint16_t d) const {
        return std::min(static_cast<int>(count.size()) - 1,
                        static_cast<int>(static_cast<float>(d) / bin_mm));
    }
    // The columns that bins lo..hi not left out reach (1 where hit).
    [[nodiscard]] std::vector<std::uint8_t> columnsHit(
        int lo, int hi, const std::vector<std::uint8_t>& leftOut) const {
        std::vector<std::uint8_t> any(columns, 0);
        for (int b = lo; b <= hi; ++b) {
            const auto i = static_cast<std::size_t>(b);
            if (count[i] == 0.0 || leftOut[i]) continue;
            const std::uint8_t* row = &columnHit[i * columns];
            for (std::size_t x = 0; x < columns; ++x) any[x] |= row[x];
        }
        return any;
    }
};

DepthHistogram histogramOf(const cv::Mat1w& depth_mm, const cv::Mat1b& mask, float bin_mm) {
    DepthHistogram h;
    h.bin_mm = bin_mm;
    h.count.assign(
        static_cast<std::size_t>(kMaxHistogramDepth_m * kMillimetresPerMetre / bin_mm) + 1, 0.0);
    h.columns = static_cast<std::size_t>(depth_mm.cols);
    h.columnHit.assign(h.count.size() * h.columns, 0);
    for (int y = 0; y < depth_mm.rows; ++y) {
        const auto* d = depth_mm[y];
        const auto* m = mask[y];
        for (int x = 0; x < depth_mm.cols; ++x)
            if (d[x] != 0 && m[x] != 0) {
                const auto b = static_cast<std::size_t>(h.binOf(d[x]));
                h.count[b] += 1.0;
                h.columnHit[b * h.columns + static_cast<std::size_t>(x)] = 1;
                h.total += 1.0;
            }
    }
    return h;
}

// Share of the masked readings in bins lo..hi (not left out) that lie in rows those bins fill
// across at least kStripeRowFill of the columns.
double stripeShare(const cv::Mat1w& depth_mm, const cv::Mat1b& mask, const DepthHistogram& h,
                   int lo, int hi, const std::vector<std::uint8_t>& leftOut) {
    double inStripes = 0.0, all = 0.0;
    const double stripe = kStripeRowFill * static_cast<double>(depth_mm.cols);
    for (int y = 0; y < depth_mm.rows; ++y) {
        const auto* d = depth_mm[y];
        const auto* m = mask[y];
        int inRow = 0;
        for (int x = 0; x < depth_mm.cols; ++x) {
            if (d[x] == 0 || m[x] == 0) continue;
            const int b = h.binOf(d[x]);
            inRow += b >= lo && b <= hi && !leftOut[static_cast<std::size_t>(b)];
        }
        all += inRow;
        if (inRow >= stripe) inStripes += inRow;
    }
    return all > 0.0 ? inStripes / all : 0.0;
}

// Whether the bins lo..hi not left out are scenery seen edge-on (kSceneryColumnCoverage);
// coverage gets the share of the image columns they reach.
bool isScenery(const cv::Mat1w& depth_mm, const cv::Mat1b& mask, const DepthHistogram& h, int lo,
               int hi, const std::vector<std::uint8_t>& leftOut, float& coverage) {
    const std::vector<std::uint8_t> hit = h.columnsHit(lo, hi, leftOut);
    const auto n = static_cast<std::ptrdiff_t>(hit.size());
    coverage = static_cast<float>(std::count(hit.begin(), hit.end(), 1)) / static_cast<float>(n);
    if (coverage <= kSceneryColumnCoverage) return false;
    const auto margin = std::max<std::ptrdiff_t>(
        1, static_cast<std::ptrdiff_t>(kSceneryBorderMargin * static_cast<float>(n)));
    const bool reachesBothSides =
        std::find(hit.begin(), hit.begin() + margin, 1) != hit.begin() + margin &&
        std::find(hit.end() - margin, hit.end(), 1) != hit.end();
    return reachesBothSides ||
           stripeShare(depth_mm, mask, h, lo, hi, leftOut) >= kSceneryStripeShare;
}

// Bins that alone are scenery (isScenery): a wall or the ground seen at an angle, where each
// depth is a stripe across the frame.
std::vector<std::uint8_t> sceneryBins(const cv::Mat1w& depth_mm, const cv::Mat1b& mask,
                                      const DepthHistogram& h) {
    std::vector<std::uint8_t> scenery(h.count.size(), 0);
    const std::vector<std::uint8_t> none(h.count.size(), 0);
    for (std::size_t b = 0; b < h.count.size(); ++b) {
        if (h.count[b] == 0.0) continue;
        float coverage = 0.f;
        const int bin = static_cast<int>(b);
        scenery[b] = isScenery(depth_mm, mask, h, bin, bin, none, coverage);
    }
    return scenery;
}

// The pixels of `mask` with a reading whose histogram bin `takesBin` takes, frame-sized.
template <class TakesBin>
cv::Mat1b pixelsOfBins(const cv::Mat1w& depth_mm, const cv::Mat1b& mask, const DepthHistogram& h,
                       TakesBin takesBin) {
    cv::Mat1b out = cv::Mat1b::zeros(depth_mm.size());
    for (int y = 0; y < depth_mm.rows; ++y)
        for (int x = 0; x < depth_mm.cols; ++x)
            if (const auto d = depth_mm(y, x); d != 0 && mask(y, x) != 0 && takesBin(h.binOf(d)))
                out(y, x) = 255;
    return out;
}

// The nearest mode with enough mass that is neither scenery nor a flat, level patch, the bins
// in `leftOut` counting as empty; found = false when there is none, with `notLeaves` set when
// the nearest such mode is not made of leaves.
DepthBand nearestMode(const DepthHistogram& h, const std::vector<std::uint8_t>& leftOut,
                      const cv::Mat1w& depth_mm, const cv::Mat1b& mask,
                      const Intrinsics& intrinsics, const SegmenterParams& params,
                      StageReport& report) {
    const int bins = static_cast<int>(h.count.size());
    const auto countAt = [&](int i) {
        return leftOut[static_cast<std::size_t>(i)] ? 0.0 : h.count[static_cast<std::size_t>(i)];
    };
    std::vector<double> smooth(h.count.size(), 0.0);
    for (int i = 0; i < bins; ++i)
        for (int k = -kSmoothHalfWidth_bins; k <= kSmoothHalfWidth_bins; ++k) {
            const int j = i + k;
            if (j >= 0 && j < bins)
                smooth[static_cast<size_t>(i)] +=
                    countAt(j) * (kSmoothHalfWidth_bins + 1 - std::abs(k));
        }
    const auto at = [&](int i) { return smooth[static_cast<size_t>(i)]; };
    const int maxHalf_bins =
        std::max(1, static_cast<int>(params.maxBandHalfWidth_m / params.histogramBin_m));
    // Modes from near to far; the first whose mass between its valleys is large enough wins.
    for (int peak = 0; peak < bins; ++peak) {
        if (at(peak) <= 0.0) continue;
        const bool isPeak = (peak == 0 || at(peak - 1) < at(peak)) &&
                            (peak == bins - 1 || at(peak + 1) <= at(peak));
        if (!isPeak) continue;
        // Widen down the mode's slopes to its valleys, and across valleys that stay above a
        // share of the peak: a tuft is several blades at different depths, and the valleys
        // between them are not the end of the tuft. Never into a bin left out.
        const double floor = kBandFloorFraction * at(peak);
        int lo = peak, hi = peak;
        const auto widen = [&](int from, int to) {
            return at(to) > 0.0 && !leftOut[static_cast<std::size_t>(to)] &&
                   (at(to) <= at(from) || at(to) > floor);
        };
        while (lo > 0 && peak - lo < maxHalf_bins && widen(lo, lo - 1)) --lo;
        while (hi < bins - 1 && hi - peak < maxHalf_bins && widen(hi, hi + 1)) ++hi;
        double mass = 0.0;
        for (int i = lo; i <= hi; ++i) mass += countAt(i);
        if (mass < params.minModeFraction * h.total || mass < params.minRegionArea_px) {
            peak = hi;  // the whole mode is too small; continue beyond it
            continue;
        }
        // A mode spread across the frame is scenery seen edge-on: the strip of ground the sensor
        // still reads before grazing angles drop it, a wall, a table edge.
        float coverage = 0.f;
        if (isScenery(depth_mm, mask, h, lo, hi, leftOut, coverage)) {
            report.notes.push_back(
                "skipped the mode at " +
                metres((static_cast<float>(peak) + 0.5f) * params.histogramBin_m) + ": it spans " +
                std::to_string(static_cast<int>(100 * coverage)) +
                " % of the image columns, across the frame (ground or wall, not a tuft)");
            peak = hi;
            continue;
        }
        const Flatness flat =
            flatness(depth_mm, mask, intrinsics, static_cast<float>(lo) * h.bin_mm,
                     static_cast<float>(hi + 1) * h.bin_mm, mass);
        if (flat.tilt_deg <= params.maxGroundTilt_deg &&
            flat.thickness_m <= params.planeDistance_m) {
            std::ostringstream s;
            s.precision(3);
            s << "skipped the mode at " << (static_cast<float>(peak) + 0.5f) * params.histogramBin_m
              << " m: a flat, level patch (" << flat.thickness_m * kMillimetresPerMetre
              << " mm thick, tilted " << flat.tilt_deg << " deg): ground, not a tuft";
            report.notes.push_back(s.str());
            peak = hi;
            continue;
        }
        // The nearest object is taken for the plant: a door's edge or a chair's back there means
        // there is no plant in view (a mode beyond it is a slice of the room, whose outlines
        // are as thin as leaves).
        const cv::Mat1b modePixels = pixelsOfBins(depth_mm, mask, h, [&](int b) {
            return b >= lo && b <= hi && !leftOut[static_cast<std::size_t>(b)];
        });
        if (const std::string unlike = unlikeLeaves(modePixels, depth_mm, intrinsics, params);
            !unlike.empty()) {
            const std::string at =
                "at " + metres((static_cast<float>(peak) + 0.5f) * params.histogramBin_m);
            report.notes.push_back("the nearest mode, " + at + ", is not leaves: " + unlike);
            DepthBand none;
            none.notLeaves = at + ", is " + unlike;
            return none;
        }
        DepthBand band;
        band.near_m = static_cast<float>(lo) * params.histogramBin_m;
        band.far_m = static_cast<float>(hi + 1) * params.histogramBin_m;
        band.found = true;
        report.notes.push_back(
            "automatic band [" + metres(band.near_m) + ", " + metres(band.far_m) +
            "]: nearest mode at " +
            metres((static_cast<float>(peak) + 0.5f) * params.histogramBin_m) + " holds " +
            std::to_string(static_cast<int>(100.0 * mass / h.total)) + " % of the valid pixels");
        return band;
    }
    report.notes.push_back("no depth mode holds " +
                           std::to_string(static_cast<int>(100.f * params.minModeFraction)) +
                           " % of the valid pixels");
    return {};
}

}  // namespace

DepthBand automaticDepthBand(const cv::Mat1w& depth_mm, const cv::Mat1b& mask,
                             const Intrinsics& intrinsics, const SegmenterParams& params,
                             bool groundRemoved, StageReport& report) {
    const DepthHistogram h =
        histogramOf(depth_mm, mask, params.histogramBin_m * kMillimetresPerMetre);
    if (h.total == 0.0) {
        report.notes.push_back("no valid depth left to histogram");
        return {};
    }
    const std::vector<std::uint8_t> none(h.count.size(), 0);
    DepthBand band = nearestMode(h, none, depth_mm, mask, intrinsics, params, report);
    if (band.found || !groundRemoved || !band.notLeaves.empty()) return band;
    // Every mode was scenery. A tuft can share one with a wall or the ground behind it: the
    // smoothing bleeds the scenery's mass into the tuft's depths, and the merged mode is skipped
    // whole and no blades are found. So look again without the bins that alone reach across the
    // frame, and keep the band from growing into their pixels. Only then, and only where a
    // ground plane was removed: otherwise the ground at the tuft's own depths fills those bins
    // too, leaving them out loses the tuft, and what is left of the ground passes for blades
    // (see docs/capture.md#depth-band).
    const std::vector<std::uint8_t> scenery = sceneryBins(depth_mm, mask, h);
    const auto sceneryCount = std::count(scenery.begin(), scenery.end(), 1);
    if (sceneryCount == 0) return band;
    double sceneryPixels = 0.0;
    for (std::size_t b = 0; b < scenery.size(); ++b)
        if (scenery[b]) sceneryPixels += h.count[b];
    report.notes.push_back(
        "looking again without " + std::to_string(sceneryCount) + " depth bin(s) of " +
        std::to_string(static_cast<long long>(sceneryPixels)) + " px that each span over " +
        std::to_string(static_cast<int>(100 * kSceneryColumnCoverage)) +
        " % of the image columns across the frame (a wall or the ground seen at an angle)");
    band = nearestMode(h, scenery, depth_mm, mask, intrinsics, params, report);
    if (!band.found) return band;
    band.scenery = pixelsOfBins(depth_mm, mask, h,
                                [&](int b) { return scenery[static_cast<std::size_t>(b)] != 0; });
    return band;
}

cv::Mat1b depthBandMask(const cv::Mat1w& depth_mm, DepthBand band, StageReport& report) {
    const double near_mm = std::floor(band.near_m * kMillimetresPerMetre);
    const double far_mm = std::ceil(band.far_m * kMillimetresPerMetre);
    cv::Mat1b mask;
    cv::inRange(depth_mm, cv::Scalar(std::max(1.0, near_mm)), cv::Scalar(far_mm), mask);
    report.notes.push_back("band " + metres(band.near_m) + " .. " + metres(band.far_m) + " keeps " +
                           std::to_string(cv::countNonZero(mask)) + " px");
    return mask;
}

void growDepthContinuous(const cv::Mat1w& depth_mm, const cv::Mat1b& allowed, DepthBand band,
                         const SegmenterParams& params, cv::Mat1b& bandMask, StageReport& report) {
    if (params.bandGrowStep_m <= 0.f) return;
    const int step_mm = static_cast<int>(std::lround(params.bandGrowStep_m * kMillimetresPerMetre));
    const int lo_mm =
        static_cast<int>((band.near_m - params.maxBandHalfWidth_m) * kMillimetresPerMetre);
    const int hi_mm =
        static_cast<int>((band.far_m + params.maxBandHalfWidth_m) * kMillimetresPerMetre);
    std::vector<cv::Point> stack;
    for (int y = 0; y < bandMask.rows; ++y)
        for (int x = 0; x < bandMask.cols; ++x)
            if (bandMask(y, x)) stack.emplace_back(x, y);
    int grown = 0;
    while (!stack.empty()) {
        const cv::Point p = stack.back();
        stack.pop_back();
        const int d0 = depth_mm(p);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const cv::Point q(p.x + dx, p.y + dy);
                if (q.x < 0 || q.y < 0 || q.x >= bandMask.cols || q.y >= bandMask.rows) continue;
                if (bandMask(q) || !allowed(q)) continue;
                const int d = depth_mm(q);
                if (d == 0 || d < lo_mm || d > hi_mm || std::abs(d - d0) > step_mm) continue;
                bandMask(q) = 255;
                ++grown;
                stack.push_back(q);
            }
    }
    report.notes.push_back("grew the band by " + std::to_string(grown) +
                           " depth-continuous px (steps <= " + std::to_string(step_mm) + " mm)");
}

}  // namespace meadow::capture::segmentation
