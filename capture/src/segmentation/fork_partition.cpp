// Who owns the fork zone: the triangles between each blade's two valleys and the base point,
// where the blades of a side-viewed tuft overlap on their way down to a shared base. The wedge
// split (blade_partition.cpp) draws each boundary there as a straight line from a valley to the
// base point, but a blade in front covers its neighbours' lower parts, and where one lies along
// another the valley sits far above the base: whole strips go to the wrong blade
// (docs/measurements/segmentation_fusion.md gives what a perfect partition would reach).
//
// Each blade's centre line, taken from its own part above the valleys, is continued down to the
// base point along a quadratic that leaves along the blade's own direction, with the width it has
// there. A zone pixel may go to any blade whose continued band holds it (within kBandReach half
// widths) or stay with its wedge; of these it goes to the one that explains it best, geometry and
// depth together: (distance / half width / kWidthSigma)^2 + ((reading - blade depth) / sigma)^2,
// the blade depth being the median reading of the blade's own pixels just outside the zone. Depth
// alone does not decide (the blades meet at one depth at the base; a blade's band can be wrong),
// nor does geometry alone (it cannot tell which blade is in front). A 3x3 majority over the zone
// then removes single-pixel decisions the sensor noise made.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <span>
#include <vector>

#include "segmentation/polyline.h"
#include "segmentation/stages.h"

namespace meadow::capture::segmentation {
namespace {

// Centre samples over which the direction of a blade's lowest visible part is taken (px).
constexpr int kTangentSpan_px = 10;
// A blade is a candidate for a pixel within this many half widths of its continued centre line.
constexpr float kBandReach = 1.5f;
// Spread of the width term: half a half width costs as much as one depth sigma.
constexpr float kWidthSigma = 0.5f;
// A blade's depth is taken from its own pixels within this distance of the zone (px).
constexpr int kDepthReach_px = 15;
constexpr int kMinDepthSamples = 10;
// Centre samples are taken as straight segments this many half widths long (at most
// kMaxSegmentSamples) for the band's distance: over 4 half widths (10-30 px) a blade's curve
// leaves its chord by well under a pixel, and shorter segments mark the same pixels again.
constexpr float kSegmentHalfWidths = 4.f;
constexpr size_t kMaxSegmentSamples = 64;
// Narrower blades (half width at their lowest visible point, px) keep their wedge and take no
// zone pixels: on a 2-4 px blade one pixel of centre-line error is a whole half width, and
// slim grass would lose pixels to its neighbours.
constexpr float kMinHalfWidth_px = 2.f;
// Nor do pieces over this many times the cluster's median width: not blades but ground or wall
// a user's depth band kept (such as the benchmark's ground strips beside its blades).
constexpr float kMaxWidthOverMedian = 3.f;

struct CentreSample {
    cv::Point2f p;
    float halfWidth_px;
};

// The piece's centre line (midpoints of its two sides matched by arc length from the tip, as the
// valleys may lie at different heights) continued to `base`; box coordinates. Empty when the
// piece is too short to give a direction.
std::vector<CentreSample> continuedCentreLine(const BladeContour& piece, cv::Point origin,
                                              cv::Point2f base) {
    const auto& c = piece.contour_px;
    const int tip = std::clamp(piece.tipIndex, 0, static_cast<int>(c.size()) - 1);
    std::vector<cv::Point2f> sideA, sideB;
    for (int i = tip; i >= 0; --i) sideA.emplace_back(c[static_cast<size_t>(i)] - origin);
    for (auto i = static_cast<size_t>(tip); i < c.size(); ++i) sideB.emplace_back(c[i] - origin);
    const auto a = resampledEvery(sideA, 1.f), b = resampledEvery(sideB, 1.f);
    const size_t n = std::min(a.size(), b.size());
    constexpr auto span = static_cast<size_t>(kTangentSpan_px);
    if (n < span + 2) return {};
    std::vector<CentreSample> line;
    line.reserve(n + 64);
    for (size_t j = 0; j < n; ++j)
        line.push_back({(a[j] + b[j]) * 0.5f, static_cast<float>(cv::norm(a[j] - b[j])) * 0.5f});
    // Direction and half width of the lowest visible part: the valleys pinch the last samples,
    // so the width is the median over the span.
    const cv::Point2f end = line[n - 1].p;
    cv::Point2f dir = end - line[n - 1 - span].p;
    const auto dirLength = static_cast<float>(cv::norm(dir));
    if (dirLength <= 0.f) return {};
    dir *= 1.f / dirLength;
    std::array<float, span + 1> widths{};
    for (size_t j = 0; j <= span; ++j) widths[j] = line[n - 1 - j].halfWidth_px;
    const float halfWidth = std::max(middleOf(std::span<float>(widths)), 0.5f);
    // The control point lies on that direction, at most halfway to the base; a base behind the
    // direction would make the curve loop, so it is a straight line then.
    const cv::Point2f toBase = base - end;
    const auto gap = static_cast<float>(cv::norm(toBase));
    const float along = dir.dot(toBase);
    const cv::Point2f control = along > 0.f ? end + dir * std::min(along, 0.5f * gap) : end;
    const int steps = std::max(1, static_cast<int>(std::ceil(gap)));
    for (int k = 1; k <= steps; ++k) {
        const float t = static_cast<float>(k) / static_cast<float>(steps);
        line.push_back(
            {end * ((1 - t) * (1 - t)) + control * (2 * (1 - t) * t) + base * (t * t), halfWidth});
    }
    return line;
}

// Work images of one call, kept per thread from frame to frame: a dozen fresh ones per cluster
// would take fresh pages from the system every frame.
struct ForkScratch {
    cv::Mat1b zone;
    cv::Mat1f band, ownScore, otherScore;
    cv::Mat1i other, decided, votes;
};
ForkScratch& forkScratch() {
    thread_local ForkScratch scratch;
    return scratch;
}
// A `size` view of `buffer`, set to `fill`; the buffer only ever grows.
template <typename T>
cv::Mat_<T> reused(cv::Mat_<T>& buffer, cv::Size size, T fill) {
    if (buffer.rows < size.height || buffer.cols < size.width)
        buffer.create(std::max(buffer.rows, size.height), std::max(buffer.cols, size.width));
    cv::Mat_<T> view = buffer(cv::Rect({0, 0}, size));
    view.setTo(fill);
    return view;
}

// Over `box` (of `zone`, only its pixels): each pixel's least distance to `line`, in the line's
// half widths there, squared, where that is within kBandReach; infinity elsewhere. The line is
// taken as segments a few half widths long (the distance to a segment is exact, and the width
// changes little along it: the mean of its ends is taken), and each segment marks the pixels it can
// reach. A distance transform over the box for each of a dozen blades cost a millisecond more per
// frame.
cv::Rect bandCost(const std::vector<CentreSample>& line, const cv::Rect& box, const cv::Mat1b& zone,
                  cv::Mat1f& costBuffer) {
    cv::Mat1f cost = reused(costBuffer, box.size(), std::numeric_limits<float>::infinity());
    cv::Rect reached;
    const cv::Point2f offset(box.tl());
    for (size_t i = 0; i + 1 < line.size();) {
        const size_t step = std::clamp<size_t>(
            static_cast<size_t>(std::lround(kSegmentHalfWidths * line[i].halfWidth_px)), 1,
            kMaxSegmentSamples);
        const size_t j = std::min(line.size() - 1, i + step);
        const cv::Point2f a = line[i].p - offset, b = line[j].p - offset;
        const float ha = line[i].halfWidth_px, hb = line[j].halfWidth_px;
        i = j;
        const float reach = kBandReach * std::max(ha, hb);
        const int x0 = std::max(0, static_cast<int>(std::ceil(std::min(a.x, b.x) - reach)));
        const int x1 =
            std::min(box.width - 1, static_cast<int>(std::floor(std::max(a.x, b.x) + reach)));
        const int y0 = std::max(0, static_cast<int>(std::ceil(std::min(a.y, b.y) - reach)));
        const int y1 =
            std::min(box.height - 1, static_cast<int>(std::floor(std::max(a.y, b.y) + reach)));
        if (x0 > x1 || y0 > y1) continue;
        reached |= cv::Rect(x0 + box.x, y0 + box.y, x1 - x0 + 1, y1 - y0 + 1);
        // One width over the segment (its ends' mean) keeps the inner loop free of divisions.
        const float h = 0.5f * (ha + hb);
        const float inverseWidth2 = 1.f / (h * h);
        const cv::Point2f ab = b - a;
        const float length2 = ab.dot(ab);
        const float inverseLength2 = length2 > 0.f ? 1.f / length2 : 0.f;
        for (int y = y0; y <= y1; ++y) {
            float* row = cost[y];
            const std::uint8_t* inZone = zone[y + box.y] + box.x;
            const float py = static_cast<float>(y) - a.y;
            for (int x = x0; x <= x1; ++x) {
                if (!inZone[x]) continue;
                const float px = static_cast<float>(x) - a.x;
                const float t = std::clamp((px * ab.x + py * ab.y) * inverseLength2, 0.f, 1.f);
                const float dx = px - ab.x * t, dy = py - ab.y * t;
                const float c2 = (dx * dx + dy * dy) * inverseWidth2;
                row[x] = std::min(row[x], c2);
            }
        }
    }
    return reached;
}

struct BladeDepth {
    bool known = false;
    float median_mm = 0.f;
};

// Median reading of each blade's own pixels (by `owner`, over the cluster's box) outside the
// zone, near it. `zone` and `zoneBox` are in the part of that box at `work`.
std::vector<BladeDepth> depthsNearZone(size_t bladeCount, const cv::Mat1i& owner,
                                       const cv::Mat1b& zone, const cv::Rect& zoneBox,
                                       cv::Point work, const cv::Mat1w& depth_mm,
                                       cv::Point origin) {
    std::vector<std::vector<std::uint16_t>> readings(bladeCount);
    const cv::Rect inZone({0, 0}, zone.size());
    const cv::Rect near =
        grownWithin(zoneBox + work, kDepthReach_px, cv::Rect({0, 0}, owner.size()));
    // Every other row and column: a median over a few hundred readings needs no more.
    for (int y = near.y; y < near.br().y; y += 2)
        for (int x = near.x; x < near.br().x; x += 2) {
            const int k = owner(y, x) - 1;
            const cv::Point z(x - work.x, y - work.y);
            if (k < 0 || (inZone.contains(z) && zone(z))) continue;
            const std::uint16_t reading = depth_mm(y + origin.y, x + origin.x);
            if (reading > 0) readings[static_cast<size_t>(k)].push_back(reading);
        }
    std::vector<BladeDepth> out(bladeCount);
    for (size_t k = 0; k < bladeCount; ++k) {
        auto& r = readings[k];
        if (r.size() < static_cast<size_t>(kMinDepthSamples)) continue;
        out[k] = {true, static_cast<float>(middleOf(std::span<std::uint16_t>(r)))};
    }
    return out;
}

}  // namespace

int assignForkZone(std::span<const BladeContour> pieces, cv::Point origin, cv::Point2f base_px,
                   const cv::Mat1b& region, const cv::Mat1w& depth_mm, float depthSigma_mm,
                   cv::Mat1i& owner) {
    if (pieces.size() < 2 || depth_mm.empty()) return 0;
    const size_t n = pieces.size();
    std::vector<std::vector<CentreSample>> lines(n);  // in the cluster's box
    std::vector<float> halfWidths;
    for (size_t k = 0; k < n; ++k) {
        lines[k] = continuedCentreLine(pieces[k], origin, base_px);
        if (!lines[k].empty()) halfWidths.push_back(lines[k].back().halfWidth_px);
    }
    if (halfWidths.empty()) return 0;
    const float widest = kMaxWidthOverMedian * middleOf(std::span<float>(halfWidths));
    // Blades left out keep their wedge and take no zone pixels.
    std::vector<char> leftOut(n, 0);
    for (size_t k = 0; k < n; ++k)
        leftOut[k] = lines[k].empty() || lines[k].back().halfWidth_px < kMinHalfWidth_px ||
                     lines[k].back().halfWidth_px > widest;

    // The zone: the triangles of the blades that take part, over their box and one pixel more
    // (the majority reads around it).
    const cv::Point base(cvRound(base_px.x), cvRound(base_px.y));
    std::vector<std::vector<cv::Point>> triangles;
    cv::Rect triangleBox(base, cv::Size(1, 1));
    for (size_t k = 0; k < n; ++k) {
        const auto& c = pieces[k].contour_px;
        if (leftOut[k] || c.size() < 2) continue;
        triangles.push_back({c.front() - origin, c.back() - origin, base});
        triangleBox |= cv::boundingRect(triangles.back());
    }
    if (triangles.empty()) return 0;
    const cv::Rect work = grownWithin(triangleBox, 1, cv::Rect({0, 0}, owner.size()));
    if (work.empty()) return 0;
    ForkScratch& scratch = forkScratch();
    cv::Mat1b zone = reused(scratch.zone, work.size(), std::uint8_t{0});
    for (auto& t : triangles) {
        for (auto& p : t) p -= work.tl();
        cv::fillConvexPoly(zone, t, 255, cv::LINE_8);
    }
    zone &= region(work);
    const cv::Rect zoneBox = cv::boundingRect(zone);  // in `work`
    if (zoneBox.empty()) return 0;
    cv::Mat1i own = owner(work);  // a view: the zone's new owners are written through it
    const auto depth = depthsNearZone(n, owner, zone, zoneBox, work.tl(), depth_mm, origin);

    // Each pixel keeps its wedge's blade unless another explains it better. The wedge's blade
    // stays a candidate outside its band, at the band's edge.
    constexpr float kReach2 = kBandReach * kBandReach;
    const auto score = [&](size_t k, float c2, std::uint16_t reading) {
        // c2: squared distance in half widths.
        float sc = std::min(c2, kReach2) / (kWidthSigma * kWidthSigma);
        if (depth[k].known && reading > 0) {
            const float dz = (static_cast<float>(reading) - depth[k].median_mm) / depthSigma_mm;
            sc += dz * dz;
        }
        return sc;
    };
    const cv::Point frame = origin + work.tl();  // work pixel (0, 0) in the frame
    const auto readingAt = [&](int y, int x) { return depth_mm(y + frame.y, x + frame.x); };
    // Over the zone's box: the wedge blade's score (< 0: the pixel is not re-decided), and the
    // best other candidate's.
    cv::Mat1f ownScore = reused(scratch.ownScore, zoneBox.size(), -1.f);
    cv::Mat1f otherScore =
        reused(scratch.otherScore, zoneBox.size(), std::numeric_limits<float>::infinity());
    cv::Mat1i other = reused(scratch.other, zoneBox.size(), 0);
    for (int y = zoneBox.y; y < zoneBox.br().y; ++y)
        for (int x = zoneBox.x; x < zoneBox.br().x; ++x) {
            const int now = own(y, x) - 1;
            if (!zone(y, x) || (now >= 0 && leftOut[static_cast<size_t>(now)])) continue;
            ownScore(y - zoneBox.y, x - zoneBox.x) =
                now < 0 ? std::numeric_limits<float>::infinity()
                        : score(static_cast<size_t>(now), kReach2, readingAt(y, x));
        }
    const cv::Point2f shift(work.tl());
    for (size_t k = 0; k < n; ++k) {
        if (leftOut[k]) continue;
        for (auto& sample : lines[k]) sample.p -= shift;
        const cv::Rect reached = bandCost(lines[k], zoneBox, zone, scratch.band);  // in `work`
        const int label = static_cast<int>(k) + 1;
        for (int y = reached.y; y < reached.br().y; ++y)
            for (int x = reached.x; x < reached.br().x; ++x) {
                const int zy = y - zoneBox.y, zx = x - zoneBox.x;
                float& mine = ownScore(zy, zx);
                const float c2 = scratch.band(zy, zx);
                if (mine < 0.f || c2 > kReach2) continue;
                const float sc = score(k, c2, readingAt(y, x));
                if (own(y, x) == label)
                    mine = sc;
                else if (sc < otherScore(zy, zx))
                    otherScore(zy, zx) = sc, other(zy, zx) = label;
            }
    }
    cv::Mat1i decided = reused(scratch.decided, work.size(), 0);
    own.copyTo(decided);
    for (int y = zoneBox.y; y < zoneBox.br().y; ++y)
        for (int x = zoneBox.x; x < zoneBox.br().x; ++x) {
            const int zy = y - zoneBox.y, zx = x - zoneBox.x;
            if (ownScore(zy, zx) >= 0.f && otherScore(zy, zx) < ownScore(zy, zx))
                decided(y, x) = other(zy, zx);
        }
    // 3x3 majority over the zone, among blades that take part (ties to the lower index). The
    // votes: each pixel's blade, 0 outside the cluster or for a blade left out, with a border
    // of zeros so that no read needs a bounds test.
    cv::Mat1i votes = reused(scratch.votes, work.size() + cv::Size(2, 2), 0);
    const cv::Mat1b area = region(work);
    for (int y = 0; y < work.height; ++y)
        for (int x = 0; x < work.width; ++x) {
            const int l = decided(y, x);
            if (l > 0 && area(y, x) && !leftOut[static_cast<size_t>(l - 1)])
                votes(y + 1, x + 1) = l;
        }
    std::vector<int> tally(n + 1, 0);
    int changed = 0;
    for (int y = zoneBox.y; y < zoneBox.br().y; ++y)
        for (int x = zoneBox.x; x < zoneBox.br().x; ++x) {
            if (ownScore(y - zoneBox.y, x - zoneBox.x) < 0.f) continue;
            const int here = decided(y, x);
            std::array<int, 9> seen{};
            int count = 0;
            bool uniform = true;
            for (int dy = 0; dy < 3; ++dy) {
                const int* row = votes[y + dy] + x;  // votes(y + dy, x): pixel (y + dy - 1, x - 1)
                for (int dx = 0; dx < 3; ++dx)
                    if (const int l = row[dx]; l > 0) {
                        seen[static_cast<size_t>(count++)] = l;
                        uniform = uniform && l == here;
                    }
            }
            int winner = here;  // where its neighbours all agree (most of the zone)
            if (!uniform) {
                int most = 0;
                for (int i = 0; i < count; ++i) {
                    const int l = seen[static_cast<size_t>(i)];
                    const int v = ++tally[static_cast<size_t>(l)];
                    if (v > most || (v == most && l < winner)) most = v, winner = l;
                }
                for (int i = 0; i < count; ++i)
                    tally[static_cast<size_t>(seen[static_cast<size_t>(i)])] = 0;
            }
            if (winner != own(y, x)) {
                own(y, x) = winner;
                ++changed;
            }
        }
    return changed;
}

}  // namespace meadow::capture::segmentation
