// Recurring readings (recurring_readings.h): per pixel, the nearest depth that enough frames
// read within a few millimetres of one another.
#include "meadow/capture/recurring_readings.h"

#include <cmath>
#include <opencv2/core.hpp>
#include <vector>

#include "meadow/capture/error.h"
#include "segmentation/sorted_readings.h"

namespace meadow::capture {

namespace {
constexpr int kMaxAgreement_mm = 1000;
}  // namespace

std::string RecurringParams::problem() const {
    if (!std::isfinite(minShare) || minShare < 0.f || minShare > 1.f)
        return "RecurringParams::minShare must be in [0, 1], got " + std::to_string(minShare);
    if (minFrames < 1)
        return "RecurringParams::minFrames must be >= 1, got " + std::to_string(minFrames);
    if (agreement_mm < 0 || agreement_mm > kMaxAgreement_mm)
        return "RecurringParams::agreement_mm must be in [0, " + std::to_string(kMaxAgreement_mm) +
               "], got " + std::to_string(agreement_mm);
    return {};
}

RecurringReadings recurringReadings(std::span<const DepthFrame> frames,
                                    const RecurringParams& params) {
    if (const std::string why = params.problem(); !why.empty())
        throw CaptureError(why + "; fix the recurring-readings parameters");
    if (frames.empty()) throw CaptureError("recurringReadings: no frames given");
    const cv::Size size = frames.front().depth_mm.size();
    for (const DepthFrame& f : frames)
        if (f.depth_mm.size() != size)
            throw CaptureError("recurringReadings: frame " + std::to_string(f.index) +
                               " differs in size from frame " +
                               std::to_string(frames.front().index) +
                               "; recurring readings need frames of one camera");
    RecurringReadings out;
    out.frames = static_cast<int>(frames.size());
    out.neededFrames =
        segmentation::framesForShare(params.minShare, frames.size(), params.minFrames);
    if (static_cast<std::size_t>(out.neededFrames) > frames.size()) {
        out.depth_mm = cv::Mat1w(size, std::uint16_t{0});  // too few frames for anything to recur
        return out;
    }
    out.depth_mm = segmentation::nearestRecurring(segmentation::sortedReadings(frames),
                                                  out.neededFrames, params.agreement_mm);
    out.recurringPixels = cv::countNonZero(out.depth_mm);
    return out;
}

}  // namespace meadow::capture
