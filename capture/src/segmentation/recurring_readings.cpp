// Recurring readings (recurring_readings.h): per pixel, the nearest depth that enough frames
// read within a few millimetres of one another.
#include "meadow/capture/recurring_readings.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "meadow/capture/error.h"

namespace meadow::capture {

namespace {
constexpr int kMaxAgreement_mm = 1000;
}

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
        std::max(params.minFrames,
                 static_cast<int>(std::ceil(params.minShare * static_cast<float>(out.frames))));
    out.depth_mm = cv::Mat1w(size, std::uint16_t{0});
    const auto needed = static_cast<std::size_t>(out.neededFrames);
    if (needed > frames.size()) return out;  // too few frames for anything to recur
    std::vector<std::uint16_t> values;
    values.reserve(frames.size());
    std::vector<const std::uint16_t*> rows(frames.size());
    for (int y = 0; y < size.height; ++y) {
        for (std::size_t i = 0; i < frames.size(); ++i) rows[i] = frames[i].depth_mm[y];
        std::uint16_t* result = out.depth_mm[y];
        for (int x = 0; x < size.width; ++x) {
            values.clear();
            for (const std::uint16_t* row : rows)
                if (row[x] != 0) values.push_back(row[x]);
            if (values.size() < needed) continue;
            std::sort(values.begin(), values.end());
            // The nearest run of `needed` readings that agree: a tip in front of the wall is the
            // nearer surface, and the wall's readings agree with one another too.
            for (std::size_t i = 0; i + needed <= values.size(); ++i)
                if (values[i + needed - 1] - values[i] <= params.agreement_mm) {
                    result[x] = values[i + (needed - 1) / 2];
                    ++out.recurringPixels;
                    break;
                }
        }
    }
    return out;
}

}  // namespace meadow::capture
