// Tip trails: a blade's tip narrows below two pixels, where the sensor's lateral noise hands
// about half of its pixels to the background. What is left is a dotted line of in-band
// readings that the outlier filter and the clean-up remove, so the mask's blade ends 20-50 px
// short of its tip. Here such dotted lines are found among the in-band readings the mask left
// out and linked back onto the mask, one pixel wide.
//
// A trail is told from the ragged edge beside a blade by how far it reaches from the mask:
// edge speckle stays within a pixel or two of it, a tip runs on for many pixels.
#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {
namespace {

// Links from one trail to the mask land within this many pixels of its first one.
constexpr int kAttachSpread_px = 2;
// A tip seen from where a trail leaves it (continuesTheMask).
constexpr int kTipRadius_px = 5;
constexpr double kTipCover = 0.4;
constexpr double kMaxTurn_deg = 50.0;
// Joined readings of a trail (readings dilated to bridge the gaps) are at most this wide.
constexpr int kMaxTrailWidth_px = 6;

// Fills the 4-connected background regions of `mask` of at most maxArea_px that border a pixel
// of `added` and touch no side of `mask` (a region cut by a side counts as open: pass a view
// that reaches maxArea_px past `added` on every side). Flood fills from `added`, capped, so the
// cost follows the trails, not the view. Returns the pixels filled.
int fillSlivers(cv::Mat1b& mask, const cv::Mat1b& added, int maxArea_px) {
    // Which fill reached a pixel first (0: none). A fill that stopped early (too large, or at a
    // side) leaves its pixels marked: a later fill that meets them is open too.
    cv::Mat1i seenBy(mask.size(), 0);
    std::vector<cv::Point> region;
    int filled = 0, fills = 0;
    const std::array<cv::Point, 4> kFour{{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
    const cv::Rect inside({0, 0}, mask.size());
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x) {
            if (!added(y, x)) continue;
            for (const cv::Point d : kFour) {
                const cv::Point start = cv::Point(x, y) + d;
                if (!inside.contains(start) || mask(start) || seenBy(start)) continue;
                const int id = ++fills;
                region.assign(1, start);
                seenBy(start) = id;
                bool open = false;
                for (size_t head = 0; head < region.size() && !open; ++head) {
                    for (const cv::Point e : kFour) {
                        const cv::Point q = region[head] + e;
                        if (!inside.contains(q)) {
                            open = true;  // reaches a side
                            break;
                        }
                        if (mask(q) || seenBy(q) == id) continue;
                        if (seenBy(q) != 0) {
                            open = true;  // joins a region already found open
                            break;
                        }
                        seenBy(q) = id;
                        region.push_back(q);
                    }
                    open |= static_cast<int>(region.size()) > maxArea_px;
                }
                if (open) continue;
                for (const cv::Point q : region) mask(q) = 255;
                filled += static_cast<int>(region.size());
            }
        }
    return filled;
}

// One trail of a group of readings: where it meets the mask, and its readings from there out.
struct TrailPart {
    cv::Point attachedAt;
    std::vector<cv::Point> readings;
};

// A group of readings can hold the trails of several tips, joined through readings along the
// mask's edge between them; readings recurring over many frames join more of them. So `trail` is
// split by where it meets the mask: each reading that `attachment` links to a mask pixel (x < 0:
// none within reach) attaches there, attachments within kAttachSpread_px of one found before
// (nearest the mask first, by `distance`) being one; every other reading goes to the part whose
// flood fill over the readings (`step` px apart at most, chessboard) reaches it first, so each
// part's readings run from the mask outward. Readings no fill reaches are left out: they join
// the rest only through edge readings that touch the mask.
template <class Attachment, class Distance>
std::vector<TrailPart> splitByAttachment(std::vector<cv::Point> trail, const cv::Rect& local,
                                         Attachment attachment, Distance distance, int step) {
    std::sort(trail.begin(), trail.end(),
              [&](cv::Point a, cv::Point b) { return distance(a) < distance(b); });
    cv::Mat1i index(local.size(), -1);
    for (size_t i = 0; i < trail.size(); ++i) index(trail[i] - local.tl()) = static_cast<int>(i);
    std::vector<TrailPart> parts;
    std::vector<int> partOf(trail.size(), -1);
    std::vector<size_t> order;  // flood fill queue, every part's attaching readings first
    for (size_t i = 0; i < trail.size(); ++i) {
        const cv::Point at = attachment(trail[i]);
        if (at.x < 0) continue;
        const auto same = std::find_if(parts.begin(), parts.end(), [&](const TrailPart& p) {
            return std::abs(at.x - p.attachedAt.x) <= kAttachSpread_px &&
                   std::abs(at.y - p.attachedAt.y) <= kAttachSpread_px;
        });
        partOf[i] = static_cast<int>(same - parts.begin());
        if (same == parts.end()) parts.push_back({at, {}});
        order.push_back(i);
    }
    for (size_t head = 0; head < order.size(); ++head) {
        const cv::Point p = trail[order[head]] - local.tl();
        for (int dy = -step; dy <= step; ++dy)
            for (int dx = -step; dx <= step; ++dx) {
                const cv::Point q = p + cv::Point(dx, dy);
                if (q.x < 0 || q.y < 0 || q.x >= local.width || q.y >= local.height) continue;
                const int j = index(q);
                if (j < 0 || partOf[static_cast<size_t>(j)] >= 0) continue;
                partOf[static_cast<size_t>(j)] = partOf[order[head]];
                order.push_back(static_cast<size_t>(j));
            }
    }
    for (const size_t i : order) parts[static_cast<size_t>(partOf[i])].readings.push_back(trail[i]);
    return parts;
}

// Whether a trail leaving the mask at `at` runs on out of a tip: the mask near `at` is narrow
// (covers at most kTipCover of a disc of kTipRadius_px) and lies behind it, opposite the trail's
// far end (within kMaxTurn_deg). A group of readings beside a blade's side fails both: the
// mask there fills about half the disc, and the readings run along the side.
template <class Distance>
bool continuesTheMask(const cv::Mat1b& mask, cv::Point at, const std::vector<cv::Point>& trail,
                      Distance distance) {
    double sx = 0.0, sy = 0.0;
    int inside = 0, disc = 0;
    for (int dy = -kTipRadius_px; dy <= kTipRadius_px; ++dy)
        for (int dx = -kTipRadius_px; dx <= kTipRadius_px; ++dx) {
            if (dx * dx + dy * dy > kTipRadius_px * kTipRadius_px) continue;
            ++disc;
            const cv::Point q = at + cv::Point(dx, dy);
            if (q.x < 0 || q.y < 0 || q.x >= mask.cols || q.y >= mask.rows || !mask(q)) continue;
            ++inside;
            sx += q.x;
            sy += q.y;
        }
    if (inside == 0 || inside > kTipCover * disc) return false;
    const cv::Point2d behind = cv::Point2d(at) - cv::Point2d(sx / inside, sy / inside);
    const cv::Point far =
        *std::max_element(trail.begin(), trail.end(),
                          [&](cv::Point a, cv::Point b) { return distance(a) < distance(b); });
    const cv::Point2d out = cv::Point2d(far) - cv::Point2d(at);
    const double norms = cv::norm(behind) * cv::norm(out);
    return norms > 0.0 && behind.dot(out) >= std::cos(kMaxTurn_deg * CV_PI / 180.0) * norms;
}

}  // namespace

namespace {

// The box tip trails are sought in (the mask's box grown by the longest trail), the mask within
// it, and the in-band readings off the mask there.
struct TrailBox {
    cv::Rect box;
    cv::Mat1b inMask;  // a view of the mask: what is set in it is set in the mask
    cv::Mat1b loose;   // in-band readings off the mask (candidates and recurring readings)
    cv::Mat1b own;     // this frame's own readings among them, for the raggedness (may be empty)
    cv::Rect inBox;    // the box in its own coordinates
    int linkRadius_px = 0;  // a trail reading links to a pixel this close (or nearer)

    // A reading touches the mask (edge, not trail) when one of its eight neighbours is on it.
    [[nodiscard]] bool adjacent(cv::Point p) const {
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (const cv::Point q = p + cv::Point(dx, dy); inBox.contains(q) && inMask(q))
                    return true;
        return false;
    }
    // The mask grown by `radius` (chessboard distance, a rectangular dilation): a full distance
    // transform of the box cost more than the rest of the front end.
    [[nodiscard]] cv::Mat1b zone(int radius) const {
        cv::Mat1b z;
        cv::dilate(inMask, z,
                   cv::getStructuringElement(cv::MORPH_RECT, {2 * radius + 1, 2 * radius + 1}));
        return z;
    }
    // The nearest pixel of `on` within linkRadius_px of `p`; x < 0 when none.
    [[nodiscard]] cv::Point nearest(cv::Point p, const cv::Mat1b& on) const {
        const int window = linkRadius_px;
        cv::Point best(-1, -1);
        int bestD2 = window * window * 2 + 1;
        for (int dy = -window; dy <= window; ++dy)
            for (int dx = -window; dx <= window; ++dx) {
                const cv::Point q = p + cv::Point(dx, dy);
                if (!inBox.contains(q) || !on(q)) continue;
                if (const int d2 = dx * dx + dy * dy; d2 < bestD2) {
                    bestD2 = d2;
                    best = q;
                }
            }
        return best;
    }
};

// Readings grouped into trails: those up to `gap` px apart belong to one.
struct TrailGroup {
    std::vector<cv::Point> trail;  // its readings not touching the mask
    cv::Rect bounds;
    bool reaches = false;  // some reading lies tipTrailMinReach_px or more from the mask
};

// Trails start at readings near the mask that do not touch it; `ownSeeds`: how many of them
// are this frame's own readings.
std::vector<cv::Point> trailSeeds(const TrailBox& t, const cv::Mat1b& touching,
                                  std::size_t& ownSeeds) {
    std::vector<cv::Point> seeds;
    ownSeeds = 0;
    for (int y = 0; y < t.box.height; ++y) {
        const std::uint8_t* l = t.loose[y];
        const std::uint8_t* o = t.own.empty() ? l : t.own[y];
        const std::uint8_t* near = touching[y];
        for (int x = 0; x < t.box.width; ++x)
            if (l[x] && near[x] && !t.adjacent({x, y})) {
                seeds.emplace_back(x, y);
                ownSeeds += o[x] != 0;
            }
    }
    return seeds;
}

// Groups are grown from the seeds only (a flood fill over the sparse readings; labelling every
// component of the box costs more). A group larger than a line of the longest trail
// (kMaxTrailWidth_px times as many readings) is a surface, such as ground the band kept or a
// leaf behind, and is not followed (counted in `rejectedWide`).
std::vector<TrailGroup> groupReadings(const TrailBox& t, const std::vector<cv::Point>& seeds,
                                      const cv::Mat1b& near, const SegmenterParams& params,
                                      int& rejectedWide) {
    const int step = params.tipTrailGap_px + 1;
    const int maxGroup = kMaxTrailWidth_px * params.tipTrailMaxLength_px;
    cv::Mat1b seen(t.box.size(), std::uint8_t{0});
    std::vector<TrailGroup> groups;
    rejectedWide = 0;
    std::vector<cv::Point> queue;
    for (const cv::Point seed : seeds) {
        if (seen(seed)) continue;
        TrailGroup g;
        bool wide = false;
        queue.assign(1, seed);
        seen(seed) = 255;
        for (size_t head = 0; head < queue.size() && !wide; ++head) {
            const cv::Point p = queue[head];
            g.bounds |= cv::Rect(p, cv::Size(1, 1));
            g.reaches |= near(p) == 0;
            if (!t.adjacent(p)) g.trail.push_back(p);
            for (int dy = -step; dy <= step; ++dy)
                for (int dx = -step; dx <= step; ++dx) {
                    const cv::Point q = p + cv::Point(dx, dy);
                    if (!t.inBox.contains(q) || !t.loose(q) || seen(q)) continue;
                    seen(q) = 255;
                    queue.push_back(q);
                }
            wide = static_cast<int>(queue.size()) > maxGroup;
        }
        if (wide) {
            ++rejectedWide;
            continue;
        }
        groups.push_back(std::move(g));
    }
    return groups;
}

// What linking the groups did.
struct Linked {
    int accepted = 0, rejectedShort = 0, rejectedSideways = 0, pixels = 0;
};

// Each group split into its trails, each trail that reaches far enough and runs on out of a tip
// linked onto the mask, one pixel wide, into `added` (box coordinates).
Linked linkTrails(const TrailBox& t, const std::vector<TrailGroup>& groups, const cv::Mat1b& near,
                  const SegmenterParams& params, cv::Mat1b& added) {
    Linked out;
    const int step = params.tipTrailGap_px + 1;
    const int window = t.linkRadius_px;
    cv::Mat1b onPart(t.box.size(), std::uint8_t{0});  // the part being linked
    for (const auto& group : groups) {
        // A trail starts at the mask (its seed, which does not touch it, is among its first
        // readings) and must reach far enough from it.
        if (!group.reaches) {
            ++out.rejectedShort;
            continue;
        }
        const cv::Rect local = grownWithin(group.bounds, window + 1, t.inBox);
        cv::Mat1f distance;
        cv::distanceTransform(~t.inMask(local), distance, cv::DIST_L2, cv::DIST_MASK_5);
        const auto distanceOf = [&](cv::Point p) { return distance(p - local.tl()); };
        const auto onMask = [&](cv::Point p) { return t.nearest(p, t.inMask); };
        for (const TrailPart& part :
             splitByAttachment(group.trail, local, onMask, distanceOf, step)) {
            if (std::none_of(part.readings.begin(), part.readings.end(),
                             [&](cv::Point p) { return near(p) == 0; })) {
                ++out.rejectedShort;
                continue;
            }
            if (!continuesTheMask(t.inMask, part.attachedAt, part.readings, distanceOf)) {
                ++out.rejectedSideways;
                continue;
            }
            // Each reading links to the nearest pixel already on its part or, near where the
            // part leaves the mask, on the mask, with a one-pixel line: the trail stays connected
            // to its blade and meets it once (a second link elsewhere would close a loop, taken
            // for crossing blades, or add a spur beside it).
            onPart(local).setTo(0);
            for (const cv::Point p : part.readings) {
                cv::Point to = t.nearest(p, onPart);
                if (to.x < 0) {
                    to = t.nearest(p, t.inMask);
                    if (to.x < 0 || std::abs(to.x - part.attachedAt.x) > kAttachSpread_px ||
                        std::abs(to.y - part.attachedAt.y) > kAttachSpread_px)
                        continue;
                }
                cv::line(onPart, to, p, 255, 1, cv::LINE_8);
            }
            onPart(local).setTo(0, t.inMask(local));
            const int count = cv::countNonZero(onPart(local) & ~added(local));
            if (count == 0) continue;
            added(local) |= onPart(local);
            out.pixels += count;
            ++out.accepted;
        }
    }
    return out;
}

}  // namespace

TipTrails recoverTipTrails(const cv::Mat1b& candidates, const cv::Mat1b& recurring,
                           const SegmenterParams& params, cv::Mat1b& mask, StageReport& report) {
    if (!(params.tipTrailMinReach_px > 0.f) || candidates.empty()) return {};
    const cv::Rect maskBox = cv::boundingRect(mask);
    if (maskBox.empty()) {
        report.notes.push_back("the mask is empty: no tip to follow");
        return {};
    }
    TrailBox t;
    t.box = grownWithin(maskBox, params.tipTrailMaxLength_px, cv::Rect(0, 0, mask.cols, mask.rows));
    t.inMask = mask(t.box);
    cv::subtract(candidates(t.box), t.inMask, t.loose);  // saturating: candidates off the mask
    if (!recurring.empty()) {
        t.own = t.loose.clone();
        cv::Mat1b more;
        cv::subtract(recurring(t.box), t.inMask, more);
        t.loose |= more;
    }
    if (cv::countNonZero(t.loose) == 0) {
        report.notes.push_back("every in-band reading is on the mask: no trail to follow");
        return {};
    }
    t.inBox = cv::Rect({0, 0}, t.box.size());
    t.linkRadius_px = params.tipTrailGap_px + 1;
    const int linkRadius_px = t.linkRadius_px;
    const cv::Mat1b touching = t.zone(linkRadius_px);
    const int reach = std::max(1, static_cast<int>(std::ceil(params.tipTrailMinReach_px)));
    const cv::Mat1b near = reach - 1 == linkRadius_px ? touching : t.zone(reach - 1);
    std::size_t ownSeeds = 0;
    const std::vector<cv::Point> seeds = trailSeeds(t, touching, ownSeeds);
    // How ragged the edges are: the share of the pixels 2 to linkRadius_px outside the mask
    // that hold an in-band reading (that band is about (linkRadius_px - 1) / linkRadius_px of
    // the zone around the mask). Lateral noise of 0.8 px puts few readings there, three times
    // that many; then speckle chains reach as far as tips do and cannot be told from them.
    const double ringPixels = (cv::countNonZero(touching) - cv::countNonZero(t.inMask)) *
                              (linkRadius_px - 1.0) / linkRadius_px;
    const double ragged = ringPixels > 0.0 ? static_cast<double>(ownSeeds) / ringPixels : 0.0;
    TipTrails result;
    result.raggedness = static_cast<float>(ragged);
    if (ragged > params.tipTrailMaxRaggedness) {
        report.notes.push_back(
            "edges too ragged to follow tips: " + std::to_string(std::lround(100.0 * ragged)) +
            " % of the pixels 2-" + std::to_string(linkRadius_px) +
            " px outside the mask hold in-band readings (tipTrailMaxRaggedness " +
            std::to_string(std::lround(100.0 * params.tipTrailMaxRaggedness)) + " %)");
        return result;
    }
    int rejectedWide = 0;
    const std::vector<TrailGroup> groups = groupReadings(t, seeds, near, params, rejectedWide);
    cv::Mat1b added(t.box.size(), std::uint8_t{0});
    Linked linked = linkTrails(t, groups, near, params, added);
    if (linked.rejectedSideways > 0)
        report.notes.push_back(std::to_string(linked.rejectedSideways) +
                               " reading group(s) leave the mask sideways, not out of a tip: "
                               "edge noise, not followed");
    if (rejectedWide > 0)
        report.notes.push_back(
            std::to_string(rejectedWide) +
            " reading group(s) beside the mask too wide for a tip: not followed");
    if (linked.rejectedShort > 0)
        report.notes.push_back(std::to_string(linked.rejectedShort) +
                               " reading group(s) beside the mask reach less than " +
                               std::to_string(params.tipTrailMinReach_px).substr(0, 4) +
                               " px from it: edge noise, not tips");
    if (linked.accepted == 0) {
        report.notes.push_back("no tip trail found");
        return result;
    }
    t.inMask.setTo(255, added);
    // A trail that runs beside its blade for a few pixels before it meets it encloses a sliver
    // of background; such slivers are filled as the clean-up fills small holes.
    // A sliver of at most maxHoleArea_px beside a trail lies within that distance of it.
    const cv::Rect sliverBox =
        grownWithin(cv::boundingRect(added), params.maxHoleArea_px + 1, t.inBox);
    cv::Mat1b sliverMask = t.inMask(sliverBox);
    linked.pixels += fillSlivers(sliverMask, added(sliverBox), params.maxHoleArea_px);
    report.notes.push_back(std::to_string(linked.accepted) +
                           " tip trail(s) of dotted in-band readings " +
                           "linked back onto the mask (" + std::to_string(linked.pixels) + " px)");
    const cv::Rect addedBox = cv::boundingRect(added);
    result.box = addedBox + t.box.tl();
    result.added = added(addedBox).clone();
    return result;
}

}  // namespace meadow::capture::segmentation
