// A blade narrower than about 3 px reaches the sensor broken: lateral noise hands stretches of
// it to the wall behind, and the clean-up leaves a stalk joined to the tuft and one or more
// fragments farther up, each under half the blade, so none matches it. Here
// each small elongated fragment looks past both of its ends, along its own axis, for another
// part of the mask; where one lies within fragmentLinkGap_px and within fragmentLinkAngle_deg
// of that axis, a line of the fragment's width joins them. Parts that are not fragments (a tuft,
// a blade as a whole) are only ever the target of a link.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {
namespace {

// Fewer pixels give no direction worth following.
constexpr size_t kMinFragmentPixels = 10;
// A link is no thicker than this: a fragment as wide is no thin blade.
constexpr int kMaxLinkWidth_px = 5;

struct Link {
    cv::Point from, to;
    int width_px;
};

// The fragment's two ends along its principal axis, each with the direction out of it, and its
// mean width; nothing when it is not elongated enough.
struct Ends {
    cv::Point end[2];
    cv::Point2f out[2];
    float width_px = 0.f;
};

bool fragmentEnds(const std::vector<cv::Point>& pixels, float minAspect, Ends& ends) {
    cv::Mat1f data(static_cast<int>(pixels.size()), 2);
    for (size_t k = 0; k < pixels.size(); ++k) {
        data(static_cast<int>(k), 0) = static_cast<float>(pixels[k].x);
        data(static_cast<int>(k), 1) = static_cast<float>(pixels[k].y);
    }
    const cv::PCA pca(data, cv::Mat(), cv::PCA::DATA_AS_ROW);
    const float major = pca.eigenvalues.at<float>(0);
    const float minor = std::max(pca.eigenvalues.at<float>(1), 1e-3f);
    if (std::sqrt(major / minor) < minAspect) return false;
    const cv::Point2f axis(pca.eigenvectors.at<float>(0, 0), pca.eigenvectors.at<float>(0, 1));
    const cv::Point2f centre(pca.mean.at<float>(0), pca.mean.at<float>(1));
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (const auto& p : pixels) {
        const float t = (cv::Point2f(p) - centre).dot(axis);
        if (t < lo) lo = t, ends.end[0] = p;
        if (t > hi) hi = t, ends.end[1] = p;
    }
    ends.out[0] = -axis;
    ends.out[1] = axis;
    ends.width_px = static_cast<float>(pixels.size()) / std::max(1.f, hi - lo);
    return true;
}

}  // namespace

void linkFragments(const SegmenterParams& params, const cv::Mat1i& labels, const cv::Mat& stats,
                   const std::vector<char>& dropped, cv::Mat1b& mask, StageReport& report) {
    if (!(params.fragmentLinkGap_px > 0.f)) return;
    const int n = stats.rows;  // background and parts
    if (n < 3) return;         // one part: nothing to link to
    // A part counts when it is still in the mask; a fragment when it is also small. Each
    // fragment's pixels are read from its own box only: the cluster box of a user's band can
    // hold a hundred thousand pixels of ground.
    const auto kept = [&](int l) { return l > 0 && !dropped[static_cast<size_t>(l)]; };
    std::vector<std::vector<cv::Point>> pixels(static_cast<size_t>(n));
    for (int i = 1; i < n; ++i) {
        const int area = stats.at<int>(i, cv::CC_STAT_AREA);
        if (!kept(i) || area > params.fragmentMaxArea_px ||
            static_cast<size_t>(area) < kMinFragmentPixels)
            continue;
        const cv::Rect box(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                           stats.at<int>(i, cv::CC_STAT_WIDTH),
                           stats.at<int>(i, cv::CC_STAT_HEIGHT));
        auto& own = pixels[static_cast<size_t>(i)];
        own.reserve(static_cast<size_t>(area));
        for (int y = box.y; y < box.br().y; ++y)
            for (int x = box.x; x < box.br().x; ++x)
                if (labels(y, x) == i) own.emplace_back(x, y);
    }
    const float gap = params.fragmentLinkGap_px;
    const int reach = static_cast<int>(std::ceil(gap));
    const float minCos = std::cos(params.fragmentLinkAngle_deg * std::numbers::pi_v<float> / 180.f);
    std::vector<Link> links;
    for (int i = 1; i < n; ++i) {
        const auto& own = pixels[static_cast<size_t>(i)];
        if (own.empty()) continue;
        Ends ends;
        if (!fragmentEnds(own, params.fragmentMinAspect, ends)) continue;
        for (int side = 0; side < 2; ++side) {
            const cv::Point e = ends.end[side];
            const cv::Point2f out = ends.out[side];
            float nearest = std::numeric_limits<float>::max();
            cv::Point target;
            for (int dy = -reach; dy <= reach; ++dy)
                for (int dx = -reach; dx <= reach; ++dx) {
                    const cv::Point q = e + cv::Point(dx, dy);
                    if (q.x < 0 || q.y < 0 || q.x >= labels.cols || q.y >= labels.rows) continue;
                    const int l = labels(q);
                    if (!kept(l) || l == i) continue;
                    const float d = std::hypot(static_cast<float>(dx), static_cast<float>(dy));
                    if (d > gap || (static_cast<float>(dx) * out.x +
                                    static_cast<float>(dy) * out.y) < minCos * d)
                        continue;
                    if (d < nearest) nearest = d, target = q;
                }
            if (nearest <= gap)
                links.push_back({e, target,
                                 std::clamp(static_cast<int>(std::lround(ends.width_px)), 1,
                                            kMaxLinkWidth_px)});
        }
    }
    // Drawn after every search, so that a link does not decide another.
    for (const auto& l : links) cv::line(mask, l.from, l.to, 255, l.width_px, cv::LINE_8);
    if (!links.empty())
        report.notes.push_back("linked " + std::to_string(links.size()) +
                               " end(s) of thin fragments to the mask within " +
                               std::to_string(static_cast<int>(gap)) +
                               " px along their axis: a blade the sensor broke");
}

}  // namespace meadow::capture::segmentation
