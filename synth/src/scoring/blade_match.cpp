#include "meadow/synth/blade_match.h"

#include <algorithm>
#include <map>
#include <opencv2/imgproc.hpp>

namespace meadow::synth {

namespace {

// The upper middle value (0 for none).
double upperMedian(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

cv::Mat1b grownByAPixel(const cv::Mat1b& m) {
    cv::Mat1b g;
    cv::dilate(m, g, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
    return g;
}

}  // namespace

BladeMatch matchBlades(const cv::Mat1w& labels, const std::vector<capture::BladeContour>& blades,
                       bool tolerant) {
    BladeMatch m;
    double maxLabel = 0;
    cv::minMaxLoc(labels, nullptr, &maxLabel);
    std::vector<cv::Mat1b> truthMasks;
    for (int id = 1; id <= static_cast<int>(maxLabel); ++id) {
        cv::Mat1b mask = labels == id;
        if (cv::countNonZero(mask) == 0) continue;
        m.trueIds.push_back(id);
        truthMasks.push_back(std::move(mask));
    }
    std::vector<cv::Mat1b> found, foundGrown;
    for (const auto& b : blades) found.push_back(b.frameMask(labels.size()));
    if (tolerant)
        for (const auto& f : found) foundGrown.push_back(grownByAPixel(f));
    struct Pair {
        double iou;
        std::size_t t, f;
    };
    std::vector<Pair> pairs;
    for (std::size_t t = 0; t < truthMasks.size(); ++t) {
        const cv::Mat1b truthGrown = tolerant ? grownByAPixel(truthMasks[t]) : cv::Mat1b();
        for (std::size_t f = 0; f < blades.size(); ++f) {
            const double inter = tolerant ? (cv::countNonZero(found[f] & truthGrown) +
                                             cv::countNonZero(truthMasks[t] & foundGrown[f])) /
                                                2.0
                                          : cv::countNonZero(truthMasks[t] & found[f]);
            if (inter == 0) continue;
            const double uni = cv::countNonZero(truthMasks[t]) + cv::countNonZero(found[f]) - inter;
            pairs.push_back({inter / uni, t, f});
        }
    }
    std::sort(pairs.begin(), pairs.end(),
              [](const Pair& a, const Pair& b) { return a.iou > b.iou; });
    m.trueBestIou.assign(truthMasks.size(), 0.0);
    m.truePartner.assign(truthMasks.size(), -1);
    m.foundToTrueId.assign(blades.size(), 0);
    std::vector<char> foundUsed(blades.size(), 0);
    for (const Pair& p : pairs) {
        if (m.truePartner[p.t] >= 0 || foundUsed[p.f]) continue;
        m.truePartner[p.t] = static_cast<int>(p.f);
        foundUsed[p.f] = 1;
        m.trueBestIou[p.t] = p.iou;
        if (p.iou >= kMatchIou) {
            ++m.matched;
            m.foundToTrueId[p.f] = m.trueIds[p.t];
        }
    }
    return m;
}

std::vector<double> perfectPartitionIou(const cv::Mat1w& labels,
                                        const std::vector<capture::BladeContour>& blades,
                                        const BladeMatch& match) {
    std::vector<cv::Mat1b> found;
    cv::Mat1b anyFound = cv::Mat1b::zeros(labels.size());
    for (const auto& b : blades) {
        found.push_back(b.frameMask(labels.size()));
        anyFound |= found.back();
    }
    const cv::Mat1b anyTruth = labels > 0;
    std::vector<double> iou;
    for (std::size_t t = 0; t < match.trueIds.size(); ++t) {
        const cv::Mat1b truth = labels == match.trueIds[t];
        cv::Mat1b mine = truth & anyFound;
        if (match.truePartner[t] >= 0)
            mine |= found[static_cast<std::size_t>(match.truePartner[t])] & ~anyTruth;
        const double u = cv::countNonZero(truth | mine);
        iou.push_back(u > 0 ? cv::countNonZero(truth & mine) / u : 0.0);
    }
    return iou;
}

int majorityTrueBlade(const capture::BladeContour& blade, const cv::Mat1w& labels,
                      double minShare) {
    std::map<int, int> votes;
    for (int v = 0; v < blade.mask.rows; ++v)
        for (int u = 0; u < blade.mask.cols; ++u)
            if (blade.mask(v, u))
                ++votes[labels(blade.maskOrigin_px.y + v, blade.maskOrigin_px.x + u)];
    int best = 0, bestVotes = 0;
    for (const auto& [id, n] : votes)
        if (n > bestVotes) best = id, bestVotes = n;
    return bestVotes >= minShare * cv::countNonZero(blade.mask) ? best : 0;
}

MissedBlade describeMissed(const cv::Mat1w& labels, const cv::Mat1f& exact_m,
                           const cv::Mat1w& depth_mm, int id) {
    MissedBlade m;
    const cv::Mat1b mine = labels == id;
    const int area_px = cv::countNonZero(mine);
    cv::Mat1f reading;
    depth_mm.convertTo(reading, CV_32F, 0.001);
    const cv::Mat1b onSurface =
        mine & (depth_mm > 0) & (cv::abs(reading - exact_m) <= MissedBlade::kOnSurface_mm / 1000.f);
    m.readShare = area_px ? double(cv::countNonZero(onSurface)) / area_px : 0.0;
    cv::Mat1i pieces;
    m.readPieces = cv::connectedComponents(onSurface, pieces, 8) - 1;
    std::vector<double> steps;
    for (int y = 1; y + 1 < labels.rows; ++y)
        for (int x = 1; x + 1 < labels.cols; ++x) {
            if (labels(y, x) != id) continue;
            float step = -1.f;  // the largest step to a touching blade, -1 for none
            for (const cv::Point q : {cv::Point(x + 1, y), cv::Point(x - 1, y), cv::Point(x, y + 1),
                                      cv::Point(x, y - 1)})
                if (labels(q) != 0 && labels(q) != id)
                    step = std::max(step, 1000.f * std::abs(exact_m(q) - exact_m(y, x)));
            if (step >= 0.f) steps.push_back(static_cast<double>(step));
        }
    m.contact_px = static_cast<int>(steps.size());
    if (!steps.empty()) {
        m.steppedShare =
            double(std::count_if(steps.begin(), steps.end(),
                                 [](double d) { return d >= MissedBlade::kDepthStep_mm; })) /
            static_cast<double>(steps.size());
        m.medianStep_mm = upperMedian(steps);
    }
    return m;
}

}  // namespace meadow::synth
