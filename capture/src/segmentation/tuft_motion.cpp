// Whether the tuft held still (tuft_motion.h): changed readings a frame apart against several.
#include "meadow/capture/tuft_motion.h"

#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "meadow/capture/error.h"

namespace meadow::capture {

std::string MotionParams::problem() const {
    if (nearLag < 1 || farLag <= nearLag)
        return "MotionParams needs 1 <= nearLag < farLag, got " + std::to_string(nearLag) +
               " and " + std::to_string(farLag);
    if (agreement_mm < 0)
        return "MotionParams::agreement_mm must be >= 0, got " + std::to_string(agreement_mm);
    if (!std::isfinite(movedRatio) || movedRatio <= 1.f)
        return "MotionParams::movedRatio must be above 1, got " + std::to_string(movedRatio);
    if (!std::isfinite(changedEveryFrame) || changedEveryFrame <= 0.f || changedEveryFrame > 1.f)
        return "MotionParams::changedEveryFrame must be in (0, 1], got " +
               std::to_string(changedEveryFrame);
    if (!std::isfinite(minMovedShare) || minMovedShare < 0.f || minMovedShare > 1.f)
        return "MotionParams::minMovedShare must be in [0, 1], got " +
               std::to_string(minMovedShare);
    return {};
}

double TuftMotion::ratio() const {
    if (nearChanged > 0.0) return farChanged / nearChanged;
    return farChanged > 0.0 ? INFINITY : 1.0;
}

bool TuftMotion::moved(const MotionParams& params) const {
    return measured &&
           ((ratio() >= params.movedRatio && farChanged - nearChanged >= params.minMovedShare) ||
            turned(params));
}

bool TuftMotion::turned(const MotionParams& params) const {
    return measured && plantChanged >= params.changedEveryFrame;
}

std::string TuftMotion::summary(const MotionParams& params) const {
    if (!measured) return "motion not measured (too few frames or no reading in the band)";
    char line[400];
    std::snprintf(line, sizeof line,
                  "changed readings %.1f %% %d frame(s) apart, %.1f %% %d apart (%.1fx, %+.1f "
                  "points, the plant's own %.0f %%; a still tuft about 1x, a moving one from "
                  "%.1fx and %+.1f, or from %.0f %% of the plant's readings one frame apart)",
                  100.0 * nearChanged, params.nearLag, 100.0 * farChanged, params.farLag, ratio(),
                  100.0 * (farChanged - nearChanged), 100.0 * plantChanged, params.movedRatio,
                  100.0 * params.minMovedShare, 100.0 * params.changedEveryFrame);
    return line;
}

namespace {

// Of the in-band readings of `a` (within the ROI), how many have no reading within
// `agreement_mm` among the 3x3 neighbours of the same pixel in `paddedB` (b's ROI with a border
// of one empty pixel).
int changedReadings(const cv::Mat1w& a, const cv::Mat1b& inBand, const cv::Mat1w& paddedB,
                    int agreement_mm) {
    cv::Mat1b unchanged(a.size(), std::uint8_t{0}), close, read;
    cv::Mat1w difference;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const cv::Mat1w b = paddedB(cv::Rect(1 + dx, 1 + dy, a.cols, a.rows));
            cv::absdiff(a, b, difference);
            cv::compare(difference, agreement_mm, close, cv::CMP_LE);
            cv::compare(b, 0, read, cv::CMP_NE);
            unchanged |= close & read;
        }
    return cv::countNonZero(inBand & ~unchanged);
}

}  // namespace

TuftMotion tuftMotion(std::span<const DepthFrame> frames, float nearDepth_m, float farDepth_m,
                      const MotionParams& params, const cv::Mat1b& plant) {
    if (const std::string why = params.problem(); !why.empty())
        throw CaptureError(why + "; fix the motion-test parameters");
    if (!(nearDepth_m >= 0.f) || !(farDepth_m > nearDepth_m))
        throw CaptureError("tuftMotion: the band [" + std::to_string(nearDepth_m) + ", " +
                           std::to_string(farDepth_m) + "] m is empty");
    TuftMotion out;
    if (frames.size() < static_cast<std::size_t>(params.farLag) + 1) return out;
    const cv::Size size = frames.front().depth_mm.size();
    for (const DepthFrame& f : frames)
        if (f.depth_mm.size() != size)
            throw CaptureError("tuftMotion: frame " + std::to_string(f.index) +
                               " differs in size from frame " +
                               std::to_string(frames.front().index));
    // In millimetres, rounded inward; 0 (no reading) is never in the band.
    const double near_mm = std::max(1.0, std::ceil(nearDepth_m * 1000.0));
    const double far_mm = std::floor(farDepth_m * 1000.0);
    // Both shares over the same first frames, each compared with the frame lag after it: only
    // their readings are tested, so only their band is needed.
    const std::size_t pairs = frames.size() - static_cast<std::size_t>(params.farLag);
    std::vector<cv::Mat1b> inBand(pairs);
    cv::Rect roi;
    for (std::size_t i = 0; i < pairs; ++i) {
        cv::inRange(frames[i].depth_mm, near_mm, far_mm, inBand[i]);
        roi |= cv::boundingRect(inBand[i]);
    }
    if (roi.empty()) return out;
    // Only the box of the tested readings is compared (grown by the neighbourhood's pixel).
    std::vector<cv::Mat1w> padded(frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
        const cv::Rect grown = (roi - cv::Point(1, 1) + cv::Size(2, 2)) & cv::Rect({}, size);
        cv::Mat1w p(roi.height + 2, roi.width + 2, std::uint16_t{0});
        frames[i].depth_mm(grown).copyTo(
            p(cv::Rect(grown.tl() - roi.tl() + cv::Point(1, 1), grown.size())));
        padded[i] = p;
    }
    if (!plant.empty() && plant.size() != size)
        throw CaptureError("tuftMotion: the plant's mask differs in size from the frames");
    const auto share = [&](int lag, int* compared, bool plantOnly = false) {
        long changed = 0, total = 0;
        for (std::size_t i = 0; i < pairs; ++i) {
            const cv::Mat1w a = frames[i].depth_mm(roi);
            const cv::Mat1b band =
                plantOnly ? cv::Mat1b(inBand[i](roi) & plant(roi)) : cv::Mat1b(inBand[i](roi));
            total += cv::countNonZero(band);
            changed += changedReadings(a, band, padded[i + static_cast<std::size_t>(lag)],
                                       params.agreement_mm);
        }
        if (compared) *compared = static_cast<int>(total);
        return total > 0 ? static_cast<double>(changed) / static_cast<double>(total) : 0.0;
    };
    out.nearChanged = share(params.nearLag, &out.readings);
    out.farChanged = share(params.farLag, nullptr);
    out.plantChanged = plant.empty() ? out.nearChanged : share(params.nearLag, nullptr, true);
    out.measured = out.readings > 0;
    return out;
}

}  // namespace meadow::capture
