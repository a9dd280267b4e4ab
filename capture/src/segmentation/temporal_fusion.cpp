// Temporal fusion of a still tuft: per-pixel median of the valid readings. The median rejects
// flying pixels and single-frame dropouts that a mean would smear into the result.
//
// An even count of readings has two middle ones, and at a blade's edge they are often one on the
// blade and one on the wall behind (lateral noise moves the edge from frame to frame). Always
// taking the farther one shrinks every blade by the pixels the edge visits in half the frames,
// always the nearer one grows it by them. So the pixels alternate in a checkerboard between the
// nearer and the farther: the edge lies where it does on average, and the edge smoothing along
// the contour evens out the alternation.
//
// A blade under ~2 px wide is read as blade in fewer than half the frames (lateral noise hands
// the rest to the wall behind, a different half each time), so its median is the wall and the
// blade is lost. FusionMethod::NearestRecurring keeps, wherever one recurs, the nearest depth read
// alike in a given share of the frames (see docs/capture.md#temporal-fusion).
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "segmentation/sorted_readings.h"
#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {

// Two frames reading one depth within the agreement are already more than chance at a blade's
// edge (lateral noise hands a pixel 1 px outside it to the blade in a quarter of the frames, at
// scattered depths where flying pixels mix blade and wall); fewer frames would take one frame's
// noise for the scene.
constexpr int kMinRecurringFusionFrames = 2;

// Where a depth recurs over the frames, the nearest such depth replaces the median: a thin blade
// read in 5 of 12 frames is there, though the wall behind it holds the median.
void takeNearestRecurring(const std::vector<cv::Mat1w>& sorted, const SegmenterParams& params,
                          cv::Mat1w& fused, StageReport& report) {
    const int needed =
        framesForShare(params.fusionRecurringShare, sorted.size(), kMinRecurringFusionFrames);
    const cv::Mat1w nearest = nearestRecurring(sorted, needed, params.fusionAgreement_mm);
    const cv::Mat1b recurs = nearest > 0;
    const int nearer = cv::countNonZero(recurs & ((fused == 0) | (nearest < fused)));
    nearest.copyTo(fused, recurs);
    report.notes.push_back(std::to_string(cv::countNonZero(recurs)) + " px read alike (within " +
                           std::to_string(params.fusionAgreement_mm) + " mm) in at least " +
                           std::to_string(needed) + " frames take the nearest such depth; " +
                           std::to_string(nearer) + " of them nearer than their median");
}

}  // namespace

cv::Mat1w fuseFrames(std::span<const DepthFrame> frames, const SegmenterParams& params,
                     StageReport& report) {
    const cv::Size size = frames[0].depth_mm.size();
    const int n = static_cast<int>(frames.size());
    const int needed = framesForShare(params.minValidFrameFraction, frames.size(), 1);
    const std::vector<cv::Mat1w> sorted = sortedReadings(frames);
    cv::Mat1w fused(size, 0);
    std::vector<const std::uint16_t*> nth(static_cast<std::size_t>(n));
    int tooFew = 0;
    for (int y = 0; y < size.height; ++y) {
        for (int k = 0; k < n; ++k) nth[static_cast<std::size_t>(k)] = sorted[k][y];
        auto* out = fused[y];
        for (int x = 0; x < size.width; ++x) {
            int valid = 0;  // the readings sort first, no reading last
            while (valid < n && nth[static_cast<std::size_t>(valid)][x] != kNoReading) ++valid;
            if (valid == 0) continue;
            if (valid < needed) {
                ++tooFew;
                continue;
            }
            int middle = valid / 2;
            if (valid % 2 == 0 && (x + y) % 2 == 0) --middle;  // the nearer of the two
            out[x] = nth[static_cast<std::size_t>(middle)][x];
        }
    }
    report.droppedPixels = tooFew;
    report.notes.push_back("median of " + std::to_string(n) + " frames; " + std::to_string(tooFew) +
                           " px dropped: valid in fewer than " + std::to_string(needed) +
                           " frames");
    if (params.fusion == FusionMethod::NearestRecurring)
        takeNearestRecurring(sorted, params, fused, report);
    report.keptPixels = cv::countNonZero(fused);
    return fused;
}

}  // namespace meadow::capture::segmentation
