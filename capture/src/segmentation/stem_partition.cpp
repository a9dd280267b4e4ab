// Partition by the skeleton's tree (PartitionMethod::StemGraph): leaves leave a stem, or a tuft's
// base, at junctions of the mask's skeleton. The skeleton is walked from the base point; a
// skeleton pixel that two or more tips lie beyond belongs to the stem (or the shared base); each
// tip's leaf is its branch back to where it meets the stem, and every cluster pixel goes to the
// nearest branch or to the stem. Plant phenotyping tools cut leaves from a stem this way; Fan &
// Sheng's contour partition assumes blades fanning from one base, which a stem breaks.
#include <algorithm>
#include <deque>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {

constexpr int kNone = -1;
const cv::Point kNeighbours[8] = {{-1, -1}, {0, -1}, {1, -1}, {-1, 0},
                                  {1, 0},   {-1, 1}, {0, 1},  {1, 1}};

struct SkeletonTree {
    cv::Mat1i parent;        // index (y * cols + x) of the parent pixel, kNone at the root/off
    std::vector<int> order;  // pixels in breadth-first order from the root
    cv::Mat1b isTip;         // skeleton pixels with one skeleton neighbour
};

int skeletonNeighbours(const cv::Mat1b& skeleton, cv::Point p) {
    int n = 0;
    for (const cv::Point& d : kNeighbours) {
        const cv::Point q = p + d;
        n += q.x >= 0 && q.y >= 0 && q.x < skeleton.cols && q.y < skeleton.rows && skeleton(q);
    }
    return n;
}

SkeletonTree walkFrom(const cv::Mat1b& skeleton, cv::Point root) {
    SkeletonTree t{cv::Mat1i(skeleton.size(), kNone), {}, cv::Mat1b::zeros(skeleton.size())};
    cv::Mat1b seen = cv::Mat1b::zeros(skeleton.size());
    std::deque<cv::Point> queue{root};
    seen(root) = 1;
    while (!queue.empty()) {
        const cv::Point p = queue.front();
        queue.pop_front();
        t.order.push_back(p.y * skeleton.cols + p.x);
        if (skeletonNeighbours(skeleton, p) == 1 && p != root) t.isTip(p) = 255;
        for (const cv::Point& d : kNeighbours) {
            const cv::Point q = p + d;
            if (q.x < 0 || q.y < 0 || q.x >= skeleton.cols || q.y >= skeleton.rows) continue;
            if (!skeleton(q) || seen(q)) continue;
            seen(q) = 1;
            t.parent(q) = p.y * skeleton.cols + p.x;
            queue.push_back(q);
        }
    }
    return t;
}

// Tips beyond each pixel (its subtree's), counting only the tips set in `tips`.
cv::Mat1i tipsBeyond(const SkeletonTree& t, const cv::Mat1b& tips) {
    cv::Mat1i count(t.parent.size(), 0);
    const int cols = t.parent.cols;
    for (auto it = t.order.rbegin(); it != t.order.rend(); ++it) {
        const cv::Point p(*it % cols, *it / cols);
        if (tips(p)) count(p) += 1;
        if (const int up = t.parent(p); up != kNone) count(up / cols, up % cols) += count(p);
    }
    return count;
}

// The branch from `tip` back to (not including) the first pixel with two or more tips beyond
// it, which is returned as `base` (the root when there is none).
std::vector<cv::Point> branchOf(const SkeletonTree& t, const cv::Mat1i& beyond, cv::Point tip,
                                cv::Point& base) {
    std::vector<cv::Point> branch;
    const int cols = t.parent.cols;
    cv::Point p = tip;
    while (true) {
        if (beyond(p) >= 2) {
            base = p;
            return branch;
        }
        branch.push_back(p);
        const int up = t.parent(p);
        if (up == kNone) {
            base = p;
            return branch;
        }
        p = {up % cols, up / cols};
    }
}

// The stem's skeleton from the root to its pixel farthest along the tree (the highest node a
// leaf leaves at), offset by `origin`; empty when no pixel has two tips beyond it.
std::vector<cv::Point> stemLine(const SkeletonTree& t, const cv::Mat1i& beyond, cv::Point origin) {
    const int cols = t.parent.cols;
    int top = kNone;
    for (const int i : t.order)  // breadth first: the last stem pixel is the farthest
        if (beyond(i / cols, i % cols) >= 2) top = i;
    std::vector<cv::Point> line;
    for (int i = top; i != kNone; i = t.parent(i / cols, i % cols))
        line.push_back(cv::Point(i % cols, i / cols) + origin);
    std::reverse(line.begin(), line.end());
    return line;
}

}  // namespace

std::vector<BladeContour> partitionByStem(BladeCluster& cluster, const cv::Mat1b& mask,
                                          const SegmenterParams& params, int firstId,
                                          const std::optional<cv::Point2f>& plantBase,
                                          StageReport& report) {
    const cv::Rect box = cv::boundingRect(cluster.contour_px);
    cv::Mat1b region(box.size(), std::uint8_t{0});
    cv::drawContours(region, std::vector<std::vector<cv::Point>>{cluster.contour_px}, 0, 255,
                     cv::FILLED, cv::LINE_8, cv::noArray(), 0, -box.tl());
    region &= mask(box);
    cv::Mat1b skeleton;
    cv::ximgproc::thinning(region, skeleton, cv::ximgproc::THINNING_ZHANGSUEN);
    std::vector<cv::Point> onSkeleton;
    cv::findNonZero(skeleton, onSkeleton);
    if (onSkeleton.empty()) return {};

    // The root: the skeleton pixel nearest where the plant stands, or the cluster's base point.
    const cv::Point2f basePoint = plantBase.value_or(cluster.basePoint_px) - cv::Point2f(box.tl());
    const cv::Point root = *std::min_element(
        onSkeleton.begin(), onSkeleton.end(), [&](const cv::Point& a, const cv::Point& b) {
            return cv::norm(cv::Point2f(a) - basePoint) < cv::norm(cv::Point2f(b) - basePoint);
        });
    const SkeletonTree tree = walkFrom(skeleton, root);

    // Spurs of the skeleton (a bump in the edge) are not leaves: a tip whose branch is shorter
    // than minLeafBranch_px is dropped, and the branches are found again without it.
    cv::Mat1b tips = tree.isTip.clone();
    cv::Mat1i beyond = tipsBeyond(tree, tips);
    std::vector<cv::Point> tipPixels;
    cv::findNonZero(tips, tipPixels);
    int spurs = 0;
    for (const cv::Point& tip : tipPixels) {
        cv::Point base;
        if (static_cast<float>(branchOf(tree, beyond, tip, base).size()) <
            params.minLeafBranch_px) {
            tips(tip) = 0;
            ++spurs;
        }
    }
    beyond = tipsBeyond(tree, tips);
    cv::findNonZero(tips, tipPixels);

    // Label the branches on the skeleton (the stem keeps label 0 in `branchLabel`, and is
    // marked in `stem`), then give every region pixel the label of its nearest skeleton pixel.
    cv::Mat1i branchLabel(box.size(), 0);
    cv::Mat1b stem(box.size(), std::uint8_t{0});
    for (const cv::Point& p : onSkeleton)
        if (beyond(p) >= 2) stem(p) = 255;
    cluster.stemLine_px = stemLine(tree, beyond, box.tl());
    struct Leaf {
        cv::Point tip, base;
        std::vector<cv::Point> branch;
    };
    std::vector<Leaf> leaves;
    for (const cv::Point& tip : tipPixels) {
        Leaf leaf{tip, {}, {}};
        leaf.branch = branchOf(tree, beyond, tip, leaf.base);
        for (const cv::Point& p : leaf.branch) branchLabel(p) = static_cast<int>(leaves.size()) + 1;
        leaves.push_back(std::move(leaf));
    }
    cv::Mat1b sources = (branchLabel > 0) | stem;
    cv::Mat1f distance;
    cv::Mat1i nearest;
    cv::distanceTransform(~sources, distance, nearest, cv::DIST_L2, cv::DIST_MASK_5,
                          cv::DIST_LABEL_PIXEL);
    // distanceTransform numbers the source pixels; map each number to its branch (0 = stem).
    std::vector<cv::Point> sourcePixels;
    cv::findNonZero(sources, sourcePixels);
    std::vector<int> labelOf(sourcePixels.size() + 1, 0);
    for (const cv::Point& p : sourcePixels)
        labelOf[static_cast<std::size_t>(nearest(p))] = branchLabel(p);

    std::vector<BladeContour> blades;
    int stemPixels = 0;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        cv::Mat1b leafMask(box.size(), std::uint8_t{0});
        for (int y = 0; y < region.rows; ++y)
            for (int x = 0; x < region.cols; ++x)
                if (region(y, x) &&
                    labelOf[static_cast<std::size_t>(nearest(y, x))] == static_cast<int>(i) + 1)
                    leafMask(y, x) = 255;
        std::vector<std::vector<cv::Point>> contours;
        cv::findContours(leafMask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
        if (contours.empty()) continue;
        const auto& outline =
            *std::max_element(contours.begin(), contours.end(),
                              [](const auto& a, const auto& b) { return a.size() < b.size(); });
        if (static_cast<int>(outline.size()) < params.minBladeContour_px) continue;
        const auto nearestOn = [&](cv::Point p) {
            int best = 0;
            double bestD = 1e18;
            for (std::size_t k = 0; k < outline.size(); ++k) {
                const double d = cv::norm(outline[k] - p);
                if (d < bestD) bestD = d, best = static_cast<int>(k);
            }
            return best;
        };
        const int n = static_cast<int>(outline.size());
        const int baseAt = nearestOn(leaves[i].base);
        const int tipAt = nearestOn(leaves[i].tip);
        BladeContour blade;
        blade.id = firstId + static_cast<int>(blades.size());
        blade.contour_px.reserve(outline.size());
        for (int s = 0; s < n; ++s)
            blade.contour_px.push_back(outline[(baseAt + s) % n] + box.tl());
        blade.tipIndex = ((tipAt - baseAt) % n + n) % n;
        // The leaf's own pixels: the part of its share the outline encloses.
        cv::Mat1b own(box.size(), std::uint8_t{0});
        cv::drawContours(own, std::vector<std::vector<cv::Point>>{outline}, 0, 255, cv::FILLED);
        own &= leafMask;
        const cv::Rect ownBox = cv::boundingRect(own);
        blade.mask = own(ownBox).clone();
        blade.maskOrigin_px = box.tl() + ownBox.tl();
        blades.push_back(std::move(blade));
    }
    for (int y = 0; y < region.rows; ++y)
        for (int x = 0; x < region.cols; ++x)
            stemPixels += region(y, x) && labelOf[static_cast<std::size_t>(nearest(y, x))] == 0;
    report.notes.push_back(
        "cluster of " + std::to_string(cluster.area_px) + " px: " + std::to_string(blades.size()) +
        " leaf/leaves cut from a stem of " + std::to_string(stemPixels) + " px; " +
        std::to_string(spurs) + " skeleton spur(s) under " +
        std::to_string(static_cast<int>(params.minLeafBranch_px)) + " px dropped");
    cluster.cutIndices.clear();
    cluster.reference_px = cv::Point2f(root + box.tl());
    return blades;
}

}  // namespace meadow::capture::segmentation
