#pragma once
// Found blades scored against the truth's label image: which found blade is which true one
// (pixel IoU, one to one), what a perfect partition of the found mask would reach, and what
// the sensor left of a true blade that nothing matched.
#include <opencv2/core/mat.hpp>
#include <vector>

#include "meadow/capture/blade_contour.h"

namespace meadow::synth {

// A found blade is a true one when their pixel IoU reaches this.
inline constexpr double kMatchIou = 0.5;

struct BladeMatch {
    std::vector<int> trueIds;         // labels visible in the truth
    std::vector<double> trueBestIou;  // per true id: IoU of its one-to-one partner, 0 if none
    std::vector<int> truePartner;     // per true id: index of that partner, -1 if none
    std::vector<int> foundToTrueId;   // per found blade: the true id it matches, or 0
    int matched = 0;                  // partners with IoU >= kMatchIou
};

// Greedy one-to-one matching over every (true, found) pair, highest IoU first. `tolerant`
// scores with a pixel's tolerance: a found pixel within one pixel (8-neighbourhood) of a true
// blade counts as on it and a true pixel within one pixel of a found blade as found (the
// intersection is the mean of the two counts), since lateral noise alone keeps the plain IoU of
// a traced blade 1-3 px wide under 0.5.
[[nodiscard]] BladeMatch matchBlades(const cv::Mat1w& labels,
                                     const std::vector<capture::BladeContour>& blades,
                                     bool tolerant = false);

// Per true id of `match`: the IoU it would reach if every found pixel on it went to it (what a
// perfect partition of the found mask gives; the partner's pixels off every true blade stay).
[[nodiscard]] std::vector<double> perfectPartitionIou(
    const cv::Mat1w& labels, const std::vector<capture::BladeContour>& blades,
    const BladeMatch& match);

// The true blade whose label holds most of the found blade's mask, when that is at least
// minShare of the mask; 0 otherwise.
[[nodiscard]] int majorityTrueBlade(const capture::BladeContour& blade, const cv::Mat1w& labels,
                                    double minShare = 0.5);

// What the sensor left of true blade `id`: how much of it was read on its surface, in how many
// pieces, and whether a depth step parts it from the blades it touches.
struct MissedBlade {
    double readShare = 0;      // share of its pixels read within kOnSurface_mm of its surface
    int readPieces = 0;        // 8-connected pieces those readings form
    int contact_px = 0;        // its pixels that 4-touch another blade's (noise-free view)
    double steppedShare = 0;   // share of those where the depth steps by >= kDepthStep_mm
    double medianStep_mm = 0;  // median step over the contact
    static constexpr float kOnSurface_mm = 10.f;
    // 3.6 sigma of the simulated axial noise at 0.7 m; the disparity step there is 1.4 mm.
    static constexpr float kDepthStep_mm = 5.f;
};
[[nodiscard]] MissedBlade describeMissed(const cv::Mat1w& labels, const cv::Mat1f& exact_m,
                                         const cv::Mat1w& depth_mm, int id);

}  // namespace meadow::synth
