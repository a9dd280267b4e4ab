// A blade's mask lives in its bounding box; these place it in the frame.
#include "meadow/capture/blade_contour.h"

#include <limits>

namespace meadow::capture {

bool BladeContour::covers(cv::Point p_px) const {
    const cv::Point local = p_px - maskOrigin_px;
    return local.x >= 0 && local.y >= 0 && local.x < mask.cols && local.y < mask.rows &&
           mask(local) != 0;
}

cv::Mat1b BladeContour::frameMask(cv::Size frameSize) const {
    if (maskOrigin_px == cv::Point(0, 0) && mask.size() == frameSize) return mask;
    cv::Mat1b out = cv::Mat1b::zeros(frameSize);
    const cv::Rect inFrame = maskBox_px() & cv::Rect({0, 0}, frameSize);
    if (!inFrame.empty()) mask(inFrame - maskOrigin_px).copyTo(out(inFrame));
    return out;
}

int nearestPointIndex(const std::vector<cv::Point>& outline, cv::Point2f p) {
    int best = 0;
    double bestSquared = std::numeric_limits<double>::max();
    for (std::size_t i = 0; i < outline.size(); ++i) {
        const double dx = outline[i].x - static_cast<double>(p.x);
        const double dy = outline[i].y - static_cast<double>(p.y);
        if (dx * dx + dy * dy < bestSquared)
            bestSquared = dx * dx + dy * dy, best = static_cast<int>(i);
    }
    return best;
}

}  // namespace meadow::capture
