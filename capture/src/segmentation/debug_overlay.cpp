// Debug overlay in the manner of Fan & Sheng 2017, Fig. 4: depth in grey, the cluster mask
// tinted, every blade in its own colour with its id at its tip, contours, centre and base point,
// cut points, the stem; the objects plant finding left out, outlined with why.
#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "meadow/capture/error.h"
#include "meadow/core/atomic_file.h"
#include "segmentation/stages.h"

namespace meadow::capture {

namespace {
constexpr double kGoldenRatioConjugate = 0.618033988749895;  // well-spread hues, blade to blade
constexpr double kBladeAlpha = 0.6;
constexpr int kMarker_px = 9;
constexpr int kLabelOffset_px = 5;  // past the tip's circle
constexpr double kLabelScale = 0.4;
constexpr int kTextHeight_px = 12;  // of kLabelScale text, with its outline

const cv::Scalar kLeftOutInk(0, 140, 255);  // orange
const cv::Scalar kStemInk(40, 90, 130);     // brown

// Text outlined in black, to read on any colour.
void drawOutlinedText(cv::Mat3b& image, const std::string& text, cv::Point at, cv::Scalar ink) {
    cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, kLabelScale, cv::Scalar(0, 0, 0), 3);
    cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, kLabelScale, ink, 1);
}

cv::Vec3b bladeColour(int id) {
    const double hue = std::fmod(static_cast<double>(id) * kGoldenRatioConjugate, 1.0) * 180.0;
    cv::Mat3b hsv(1, 1, cv::Vec3b(static_cast<uchar>(hue), 220, 255)), bgr;
    cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
    return bgr(0, 0);
}
}  // namespace

cv::Mat3b renderDebugOverlay(const DepthFrame& frame, const Segmentation& s) {
    cv::Mat1b grey(frame.depth_mm.size(), std::uint8_t{0});
    if (!frame.depth_mm.empty()) {
        double lo = 0, hi = 0;
        cv::minMaxLoc(frame.depth_mm, &lo, &hi, nullptr, nullptr, frame.depth_mm > 0);
        if (hi > lo) {
            // Near = bright: invert depth into [40, 255]; no reading = black.
            cv::Mat1f f;
            frame.depth_mm.convertTo(f, CV_32F);
            cv::Mat1f g = 255.0 - (f - lo) * (215.0 / (hi - lo));
            g.convertTo(grey, CV_8U);
            grey.setTo(0, frame.depth_mm == 0);
        }
    } else if (!s.clusterMask.empty()) {
        grey = cv::Mat1b(s.clusterMask.size(), std::uint8_t{0});
    }
    cv::Mat3b out;
    cv::cvtColor(grey, out, cv::COLOR_GRAY2BGR);
    if (!s.clusterMask.empty() && s.clusterMask.size() == out.size())
        out.setTo(cv::Scalar(90, 60, 60), s.clusterMask);  // mask not given to any blade: slate
    // The stem's share (PartitionMethod::StemGraph) in brown: a leaf short at its base lost it
    // there when its base lies in it.
    for (const BladeCluster& c : s.clusters) {
        if (c.stemShare.empty()) continue;
        const cv::Rect box =
            cv::Rect(c.stemShareOrigin_px, c.stemShare.size()) & cv::Rect(0, 0, out.cols, out.rows);
        if (box.empty()) continue;
        out(box).setTo(kStemInk, c.stemShare(box - c.stemShareOrigin_px));
    }
    // What plant finding left out, and why: a user whose plant lacks a part sees where it went.
    for (const LeftOutObject& o : s.leftOut) {
        if (o.outline_px.empty()) continue;
        cv::polylines(out, std::vector<std::vector<cv::Point>>{o.outline_px}, true, kLeftOutInk, 1);
        const cv::Rect box = cv::boundingRect(o.outline_px);
        // Above the outline, or just inside it where the frame's top leaves no room.
        drawOutlinedText(out, o.why,
                         {box.x, box.y >= kTextHeight_px ? box.y - 3 : box.y + kTextHeight_px},
                         kLeftOutInk);
    }
    for (const auto& b : s.blades) {
        const cv::Rect box = b.maskBox_px() & cv::Rect(0, 0, out.cols, out.rows);
        const cv::Vec3b c = bladeColour(b.id);
        for (int y = box.y; y < box.br().y; ++y)
            for (int x = box.x; x < box.br().x; ++x)
                if (b.mask(y - b.maskOrigin_px.y, x - b.maskOrigin_px.x))
                    for (int ch = 0; ch < 3; ++ch)
                        out(y, x)[ch] = cv::saturate_cast<uchar>(kBladeAlpha * c[ch] +
                                                                 (1 - kBladeAlpha) * out(y, x)[ch]);
    }
    for (const auto& b : s.blades) {
        const cv::Vec3b c = bladeColour(b.id);
        cv::polylines(out, std::vector<std::vector<cv::Point>>{b.contour_px}, false, cv::Scalar(c),
                      1);
        if (b.contour_px.empty()) continue;
        const cv::Point tip = b.contour_px[static_cast<size_t>(b.tipIndex)];
        cv::circle(out, tip, 3, cv::Scalar(255, 255, 255), 1);
        // The blade's id beside its tip, as capture's notes name it ("frame 0 blade 4 skipped:
        // ..."): white, or red with a "!" when flagged; outlined in black to read on any colour.
        const std::string label = std::to_string(b.id) + (b.flags.empty() ? "" : "!");
        const cv::Scalar ink = b.flags.empty() ? cv::Scalar(255, 255, 255) : cv::Scalar(0, 0, 255);
        drawOutlinedText(out, label, tip + cv::Point(kLabelOffset_px, -kLabelOffset_px), ink);
    }
    for (const auto& c : s.clusters) {
        // The stem as the stem-graph partition found it: where the leaves' bases should lie.
        if (c.stemLine_px.size() >= 2)
            cv::polylines(out, std::vector<std::vector<cv::Point>>{c.stemLine_px}, false,
                          cv::Scalar(255, 255, 255), 2);
        cv::drawMarker(out, c.centre_px, cv::Scalar(0, 255, 255), cv::MARKER_CROSS, kMarker_px, 2);
        cv::drawMarker(out, c.basePoint_px, cv::Scalar(255, 0, 255), cv::MARKER_DIAMOND, kMarker_px,
                       2);
        for (int i : c.cutIndices)
            cv::drawMarker(out, c.contour_px[static_cast<size_t>(i)], cv::Scalar(0, 0, 255),
                           cv::MARKER_TILTED_CROSS, kMarker_px, 2);
    }
    if (s.blades.empty() && !s.noBladesReason.empty())
        cv::putText(out, "no blades: " + s.noBladesReason, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                    cv::Scalar(0, 0, 255), 1);
    return out;
}

void writeDebugOverlay(const std::filesystem::path& path, const DepthFrame& frame,
                       const Segmentation& segmentation) {
    const cv::Mat3b image = renderDebugOverlay(frame, segmentation);
    std::vector<uchar> png;
    if (image.empty() || !cv::imencode(".png", image, png))
        throw CaptureError("writeDebugOverlay: cannot encode the overlay for " + path.string() +
                           "; the frame is empty");
    try {
        writeFileAtomically(
            path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
    } catch (const Error& e) {
        throw CaptureError(std::string("writeDebugOverlay: ") + e.what());
    }
}

}  // namespace meadow::capture
