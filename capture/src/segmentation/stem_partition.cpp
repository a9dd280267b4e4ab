// Partition by the skeleton's graph (PartitionMethod::StemGraph): leaves leave a stem, or a
// tuft's base, at junctions of the mask's skeleton, and cross each other at others. The skeleton's
// edges are joined through each junction by the smoothest continuation in direction and depth
// (skeleton_strands.cpp), so a leaf that crosses another, or the stem, stays one strand. The
// strand from where the plant stands that most others end on is the stem, up to the highest node
// a leaf leaves it at; every other strand is a leaf, and every cluster pixel goes to the strand
// its nearest skeleton pixel belongs to (both, at a crossing). Plant phenotyping tools cut leaves
// from a stem this way; Fan & Sheng's contour partition assumes blades fanning from one base,
// which a stem breaks.
#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "segmentation/cluster_skeleton.h"
#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {

constexpr int kNone = -1;
constexpr int kStem = 0;  // the stem's (or a tuft's shared base's) label; leaves are 1, 2, ...

// A leaf: its skeleton, from its base (its end nearer the stem, where it leaves it; without a
// stem, the end that meets another, or the end nearer the plant's foot) to its tip.
struct LeafStrand {
    std::vector<cv::Point> path;
    cv::Point base, tip;
    bool endMeetsAnother = false;  // its far end meets another leaf or the stem, not free
};

// The image distance from `p` to the nearest pixel of `line` (not empty).
double distanceTo(cv::Point p, const std::vector<cv::Point>& line) {
    return cv::norm(line[static_cast<std::size_t>(nearestPointIndex(line, p))] - p);
}

LeafStrand leafOf(const SkeletonGraph& graph, const Strand& s, cv::Point2f plantFoot,
                  const std::vector<cv::Point>& stemLine) {
    LeafStrand leaf;
    leaf.path = s.path(graph);
    const bool startFree = graph.nodes[static_cast<std::size_t>(s.startNode)].tip;
    const bool endFree = graph.nodes[static_cast<std::size_t>(s.endNode)].tip;
    if (s.startNode == s.endNode) {  // a closed loop: its tip is its farthest point
        leaf.endMeetsAnother = true;
        leaf.base = leaf.path.front();
        leaf.tip = *std::max_element(leaf.path.begin(), leaf.path.end(), [&](auto a, auto b) {
            return cv::norm(a - leaf.base) < cv::norm(b - leaf.base);
        });
        return leaf;
    }
    leaf.endMeetsAnother = !startFree && !endFree;
    bool fromStart = !startFree && endFree;
    // A leaf arching over hangs its tip low, nearer the foot than its base may be, and its tip
    // may come to rest on another leaf: the stem is where it leaves.
    if (!stemLine.empty())
        fromStart =
            distanceTo(leaf.path.front(), stemLine) <= distanceTo(leaf.path.back(), stemLine);
    else if (startFree == endFree)  // both meet others, or neither: the end nearer the foot
        fromStart = cv::norm(cv::Point2f(leaf.path.front()) - plantFoot) <=
                    cv::norm(cv::Point2f(leaf.path.back()) - plantFoot);
    leaf.base = fromStart ? leaf.path.front() : leaf.path.back();
    leaf.tip = fromStart ? leaf.path.back() : leaf.path.front();
    return leaf;
}

// The outline of a leaf's share of the region, from its base round its tip and back.
std::optional<BladeContour> leafContour(const cv::Mat1b& leafMask, const LeafStrand& leaf,
                                        cv::Point origin, int minContour_px) {
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(leafMask, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    if (contours.empty()) return std::nullopt;
    const auto& outline =
        *std::max_element(contours.begin(), contours.end(),
                          [](const auto& a, const auto& b) { return a.size() < b.size(); });
    if (static_cast<int>(outline.size()) < minContour_px) return std::nullopt;
    const int n = static_cast<int>(outline.size());
    const int baseAt = nearestPointIndex(outline, leaf.base);
    const int tipAt = nearestPointIndex(outline, leaf.tip);
    BladeContour blade;
    blade.contour_px.reserve(outline.size());
    for (int s = 0; s < n; ++s) blade.contour_px.push_back(outline[(baseAt + s) % n] + origin);
    blade.tipIndex = ((tipAt - baseAt) % n + n) % n;
    // The leaf's own pixels: the part of its share the outline encloses.
    cv::Mat1b own(leafMask.size(), std::uint8_t{0});
    cv::drawContours(own, std::vector<std::vector<cv::Point>>{outline}, 0, 255, cv::FILLED);
    own &= leafMask;
    const cv::Rect ownBox = cv::boundingRect(own);
    blade.mask = own(ownBox).clone();
    blade.maskOrigin_px = origin + ownBox.tl();
    return blade;
}

// Each skeleton pixel's owners (labels: kStem, or a leaf's): its edge's strand's; a junction
// belongs to the strands that run through it (two at a crossing), else to the stem or shared
// base. A kink's pixel that its path stepped past takes its neighbour's owners.
struct SkeletonOwners {
    cv::Mat1i first, second;  // second: kNone but at crossings
};

SkeletonOwners ownersOnSkeleton(const SkeletonGraph& graph, const Strands& strands,
                                const std::vector<bool>& isStem,
                                const std::vector<int>& labelOfStrand,
                                const std::vector<cv::Point>& onSkeleton, cv::Size size) {
    SkeletonOwners o{cv::Mat1i(size, kNone), cv::Mat1i(size, kNone)};
    const auto labelOfEdge = [&](int e) {
        return labelOfStrand[static_cast<std::size_t>(
            strands.strandOfEdge[static_cast<std::size_t>(e)])];
    };
    for (std::size_t e = 0; e < graph.edges.size(); ++e)
        for (const cv::Point& p : graph.edges[e].pixels)
            o.first(p) = labelOfEdge(static_cast<int>(e));
    for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
        const SkeletonNode& node = graph.nodes[n];
        std::vector<int> owners;
        if (node.tip && !node.ends.empty()) owners.push_back(labelOfEdge(node.ends.front() / 2));
        for (std::size_t i = 0; i < strands.strands.size(); ++i) {
            const Strand& s = strands.strands[i];
            const int here = static_cast<int>(n);
            const bool stemEnd = isStem[i] && (s.endNode == here || s.startNode == here);
            if (stemEnd || std::find(s.through.begin(), s.through.end(), here) != s.through.end())
                if (std::find(owners.begin(), owners.end(), labelOfStrand[i]) == owners.end())
                    owners.push_back(labelOfStrand[i]);
        }
        if (owners.empty() && node.root && node.ends.size() == 1)  // a leaf standing alone
            owners.push_back(labelOfEdge(node.ends.front() / 2));
        for (const cv::Point& p : node.pixels) {
            o.first(p) = owners.empty() ? kStem : owners[0];
            o.second(p) = owners.size() > 1 ? owners[1] : kNone;
        }
    }
    const cv::Rect inside({}, size);
    for (bool again = true; again;) {
        again = false;
        for (const cv::Point& p : onSkeleton) {
            if (o.first(p) != kNone) continue;
            for (int dy = -1; dy <= 1 && o.first(p) == kNone; ++dy)
                for (int dx = -1; dx <= 1 && o.first(p) == kNone; ++dx) {
                    const cv::Point q = p + cv::Point(dx, dy);
                    if (!inside.contains(q) || o.first(q) == kNone) continue;
                    o.first(p) = o.first(q);
                    o.second(p) = o.second(q);
                    again = true;
                }
        }
    }
    for (const cv::Point& p : onSkeleton)
        if (o.first(p) == kNone) o.first(p) = kStem;
    return o;
}

// Every region pixel goes to the owners of its nearest skeleton pixel: one mask per label
// (index 0, the stem's).
std::vector<cv::Mat1b> sharesOfRegion(const cv::Mat1b& region, const cv::Mat1b& skeleton,
                                      const std::vector<cv::Point>& onSkeleton,
                                      const SkeletonOwners& owners, std::size_t leaves) {
    cv::Mat1f distance;
    cv::Mat1i nearest;
    cv::distanceTransform(~skeleton, distance, nearest, cv::DIST_L2, cv::DIST_MASK_5,
                          cv::DIST_LABEL_PIXEL);
    std::vector<cv::Point> sourceAt(onSkeleton.size() + 1);
    for (const cv::Point& p : onSkeleton) sourceAt[static_cast<std::size_t>(nearest(p))] = p;
    std::vector<cv::Mat1b> masks(leaves + 1);
    for (auto& m : masks) m = cv::Mat1b::zeros(region.size());
    for (int y = 0; y < region.rows; ++y)
        for (int x = 0; x < region.cols; ++x) {
            if (!region(y, x)) continue;
            const cv::Point s = sourceAt[static_cast<std::size_t>(nearest(y, x))];
            for (const int label : {owners.first(s), owners.second(s)})
                if (label > kStem) masks[static_cast<std::size_t>(label)](y, x) = 255;
            if (owners.first(s) == kStem) masks[kStem](y, x) = 255;
        }
    return masks;
}

// A leaf that leaves the stem low hangs below where it left, before the pot or beside it, long
// and thin; what plant finding leaves of the pot (its rim, a piece of its side) stays within the
// pot's sides, or is broad. A path (box coordinates, the box at `origin`) hangs past the pot
// when it is a leaf's length over width and reaches beyond one side of the pot by more than
// kPastPotShare of the pot's width.
constexpr float kPastPotShare = 0.25f;
bool hangsPastPot(const std::vector<cv::Point>& path, const cv::Mat1f& halfWidth,
                  const std::optional<cv::Rect>& pot, cv::Point origin) {
    if (!pot || pot->width <= 0 || path.empty()) return false;
    std::vector<float> widths;
    for (const cv::Point& p : path) widths.push_back(halfWidth(p));
    const float width = 2.f * std::max(middleOf(std::span<float>(widths)), 0.5f);
    if (static_cast<float>(path.size()) < kMinLeafElongation * width) return false;
    const float margin = kPastPotShare * static_cast<float>(pot->width);
    return std::any_of(path.begin(), path.end(), [&](cv::Point p) {
        const int x = p.x + origin.x;
        return static_cast<float>(pot->x - x) > margin ||
               static_cast<float>(x - (pot->x + pot->width - 1)) > margin;
    });
}

}  // namespace

std::vector<BladeContour> partitionByStem(BladeCluster& cluster, const cv::Mat1b& mask,
                                          const cv::Mat1w& depth_mm, const SegmenterParams& params,
                                          int firstId, const std::optional<cv::Point2f>& plantBase,
                                          const std::optional<cv::Rect>& plantPot,
                                          const std::vector<cv::Point>& plantStem_px,
                                          StageReport& report) {
    const cv::Point2f footInFrame = plantBase.value_or(cluster.basePoint_px);
    std::optional<ClusterSkeleton> skeletonOf =
        clusterSkeleton(cluster, mask, depth_mm, params, footInFrame);
    if (!skeletonOf) return {};
    ClusterSkeleton& sk = *skeletonOf;
    const cv::Rect& box = sk.box;
    const cv::Mat1b& region = sk.region;
    const cv::Mat1b& skeleton = sk.skeleton;
    const std::vector<cv::Point>& onSkeleton = sk.onSkeleton;
    const cv::Point root = sk.root;
    const SkeletonGraph& graph = sk.graph;
    Strands& strands = sk.strands;
    const cv::Point2f foot = footInFrame - cv::Point2f(box.tl());

    // The stem, and the leaves: every other strand long enough to be more than a spur.
    const std::vector<int> stem = followStem(graph, strands);
    std::vector<bool> isStem(strands.strands.size(), false);
    for (const int i : stem) isStem[static_cast<std::size_t>(i)] = true;
    std::vector<int> labelOfStrand(strands.strands.size(), kStem);
    std::vector<LeafStrand> leaves;
    int belowFoot = 0;
    float footRow = foot.y;  // the foot's row, or the root's top where that is higher
    if (graph.rootNode != kNone)
        for (const cv::Point& p : graph.nodes[static_cast<std::size_t>(graph.rootNode)].pixels)
            footRow = std::min(footRow, static_cast<float>(p.y));
    std::vector<cv::Point> stemLine;
    for (const int i : stem) {
        const std::vector<cv::Point> path =
            strands.strands[static_cast<std::size_t>(i)].path(graph);
        stemLine.insert(stemLine.end(), path.begin(), path.end());
    }
    // Leaves go by the stem they leave, though it lies in another cluster.
    std::vector<cv::Point> baseBy = stemLine;
    if (baseBy.empty())
        for (const cv::Point& p : plantStem_px) baseBy.push_back(p - box.tl());
    for (std::size_t i = 0; i < strands.strands.size(); ++i) {
        if (isStem[i]) continue;
        LeafStrand leaf = leafOf(graph, strands.strands[i], foot, baseBy);
        if (static_cast<float>(leaf.path.size()) < params.minLeafBranch_px) continue;
        // Where the plant stands is known (the top of its pot): what lies wholly below it is
        // the pot's rim or the ground, not a leaf, unless it is a low leaf hanging past the pot.
        if (plantBase &&
            std::all_of(leaf.path.begin(), leaf.path.end(),
                        [&](cv::Point p) { return p.y >= footRow; }) &&
            !hangsPastPot(leaf.path, sk.halfWidth, plantPot, box.tl())) {
            ++belowFoot;
            continue;
        }
        leaves.push_back(std::move(leaf));
        labelOfStrand[i] = static_cast<int>(leaves.size());
    }
    cluster.stemLine_px.clear();
    for (const cv::Point& p : stemLine) cluster.stemLine_px.push_back(p + box.tl());

    const SkeletonOwners owners =
        ownersOnSkeleton(graph, strands, isStem, labelOfStrand, onSkeleton, box.size());
    const std::vector<cv::Mat1b> leafMasks =
        sharesOfRegion(region, skeleton, onSkeleton, owners, leaves.size());
    const int stemPixels = cv::countNonZero(leafMasks[kStem]);
    if (!stem.empty()) {
        cluster.stemShare = leafMasks[kStem];
        cluster.stemShareOrigin_px = box.tl();
    }

    std::vector<BladeContour> blades;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
        auto blade = leafContour(leafMasks[i + 1], leaves[i], box.tl(), params.minBladeContour_px);
        if (!blade) continue;
        blade->id = firstId + static_cast<int>(blades.size());
        if (leaves[i].endMeetsAnother)
            addFlag(*blade, BladeFlag::Overlapping,
                    "its far end meets another leaf or the stem where no leaf runs on smoothly: "
                    "its tip is hidden there, or it runs on under another leaf");
        blades.push_back(std::move(*blade));
    }
    const auto crossings = crossingNodes(graph, strands).size();
    report.notes.push_back(
        "cluster of " + std::to_string(cluster.area_px) + " px: " + std::to_string(blades.size()) +
        " leaf/leaves cut from a stem of " + std::to_string(stemPixels) + " px; " +
        std::to_string(crossings) + " crossing(s) followed through; " + std::to_string(belowFoot) +
        " branch(es) wholly below the plant's foot (pot) left out; " + std::to_string(sk.spurs) +
        " skeleton spur(s) under " + std::to_string(static_cast<int>(params.minLeafBranch_px)) +
        " px dropped");
    cluster.cutIndices.clear();
    cluster.reference_px = cv::Point2f(root + box.tl());
    return blades;
}

}  // namespace meadow::capture::segmentation
