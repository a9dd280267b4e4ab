// Partition of a cluster's contour into single blades (Fan & Sheng 2017, Sec. 4.2): the
// distance of each contour point to the reference point rises along a blade to its tip and
// falls back to a local minimum where two blades part. The paper cuts at local minima; raw
// minima of a pixel contour are mostly staircase noise, so only minima whose topological
// persistence (depth below the lower of their two bounding maxima) is large are cuts.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {
constexpr float kGaussianSupport_sigmas = 3.0f;
// 1/16 (6 %) covers the 5x5 chamfer metric's departure from the Euclidean distance (< 2 %).
constexpr int kChamferMarginDivisor = 16;

int wrap(int i, int n) { return ((i % n) + n) % n; }
}  // namespace

std::vector<float> smoothCircular(std::span<const float> signal, float sigma_samples) {
    const int n = static_cast<int>(signal.size());
    if (sigma_samples <= 0.f || n < 3) return {signal.begin(), signal.end()};
    const int half =
        std::min(n / 2, static_cast<int>(std::ceil(kGaussianSupport_sigmas * sigma_samples)));
    const cv::Mat1f kernel = cv::getGaussianKernel(2 * half + 1, sigma_samples, CV_32F);
    std::vector<float> out(signal.size(), 0.f);
    for (int i = 0; i < n; ++i) {
        float acc = 0.f;
        for (int k = -half; k <= half; ++k)
            acc += kernel(k + half) * signal[static_cast<size_t>(wrap(i + k, n))];
        out[static_cast<size_t>(i)] = acc;
    }
    return out;
}

// Sublevel-set persistence on a cycle: samples are added from low to high; a sample with no
// active neighbour starts a component (a minimum is born); a sample joining two components
// kills the younger one (higher birth value) with persistence = value - birth (elder rule).
std::vector<std::pair<int, float>> circularMinimaPersistence(std::span<const float> signal) {
    const int n = static_cast<int>(signal.size());
    std::vector<std::pair<int, float>> result;
    if (n == 0) return result;
    std::vector<int> order(static_cast<size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return signal[static_cast<size_t>(a)] < signal[static_cast<size_t>(b)];
    });
    std::vector<int> parent(static_cast<size_t>(n), -1);  // -1 = not yet active
    std::vector<int> birthIndex(static_cast<size_t>(n), -1);
    const auto find = [&](int i) {
        while (parent[static_cast<size_t>(i)] != i) {
            parent[static_cast<size_t>(i)] =
                parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
            i = parent[static_cast<size_t>(i)];
        }
        return i;
    };
    const auto birth = [&](int root) {
        return signal[static_cast<size_t>(birthIndex[static_cast<size_t>(root)])];
    };
    for (int i : order) {
        parent[static_cast<size_t>(i)] = i;
        birthIndex[static_cast<size_t>(i)] = i;
        bool joined = false;
        for (int j : {wrap(i - 1, n), wrap(i + 1, n)}) {
            if (j == i || parent[static_cast<size_t>(j)] < 0) continue;
            const int ri = find(i), rj = find(j);
            if (ri == rj) continue;
            if (!joined) {  // i joins its first neighbour's component: no new minimum
                parent[static_cast<size_t>(ri)] = rj;
                joined = true;
                continue;
            }
            // i bridges two components: the younger minimum dies here.
            const int young = birth(ri) > birth(rj) || (birth(ri) == birth(rj) &&
                                                        birthIndex[static_cast<size_t>(ri)] >
                                                            birthIndex[static_cast<size_t>(rj)])
                                  ? ri
                                  : rj;
            const int old = young == ri ? rj : ri;
            result.emplace_back(birthIndex[static_cast<size_t>(young)],
                                signal[static_cast<size_t>(i)] - birth(young));
            parent[static_cast<size_t>(young)] = old;
        }
        if (!joined) {
            // A new component born at i (a local minimum); nothing to record yet.
        }
    }
    result.emplace_back(birthIndex[static_cast<size_t>(find(order.front()))],
                        std::numeric_limits<float>::infinity());
    std::sort(result.begin(), result.end());
    // Drop zero-persistence entries (plateau samples joining at their own level).
    std::erase_if(result, [](const auto& r) { return r.second <= 0.f; });
    return result;
}

namespace {

// Where the contour is cut: the minima of its distance to the reference whose persistence
// reaches the threshold, merged where a piece between two would be too short to be a blade.
struct Cuts {
    std::vector<std::pair<int, float>> minima;  // every minimum, with its persistence
    std::vector<std::pair<int, float>> cuts;    // those that cut, in contour order
    float threshold = 0.f;
};

Cuts persistentCuts(BladeCluster& cluster, const SegmenterParams& params, StageReport& report) {
    const auto& contour = cluster.contour_px;
    const int n = static_cast<int>(contour.size());
    std::vector<float> raw(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
        raw[static_cast<size_t>(i)] = static_cast<float>(
            cv::norm(cv::Point2f(contour[static_cast<size_t>(i)]) - cluster.reference_px));
    cluster.distance_px = smoothCircular(raw, params.smoothingSigma_px);
    const auto& d = cluster.distance_px;
    const float maxDistance = *std::max_element(d.begin(), d.end());
    Cuts out;
    out.threshold = std::max(params.minPersistence_px, params.minPersistenceFraction * maxDistance);
    out.minima = circularMinimaPersistence(d);
    int weak = 0;
    for (const auto& m : out.minima) {
        if (m.second >= out.threshold)
            out.cuts.push_back(m);
        else
            ++weak;
    }
    // Pieces too short to be a blade merge into a neighbour: drop the weaker of their two cuts.
    auto& cuts = out.cuts;
    int merged = 0;
    for (bool changed = true; changed && cuts.size() > 1;) {
        changed = false;
        for (size_t k = 0; k < cuts.size(); ++k) {
            const size_t next = (k + 1) % cuts.size();
            const int length = wrap(cuts[next].first - cuts[k].first, n);
            if (length >= params.minBladeContour_px) continue;
            cuts.erase(cuts.begin() +
                       static_cast<std::ptrdiff_t>(cuts[k].second < cuts[next].second ? k : next));
            ++merged;
            changed = true;
            break;
        }
    }
    report.notes.push_back(
        "cluster of " + std::to_string(cluster.area_px) + " px: " + std::to_string(cuts.size()) +
        " cut(s) at persistence >= " + std::to_string(out.threshold) + " px; " +
        std::to_string(weak) + " shallow minima ignored, " + std::to_string(merged) +
        " piece(s) shorter than minBladeContour_px merged");
    cluster.cutIndices.clear();
    for (const auto& c : cuts) cluster.cutIndices.push_back(c.first);
    return out;
}

// The contour between each cut and the next, its tip the farthest point from the reference.
std::vector<BladeContour> contourPieces(const BladeCluster& cluster, const Cuts& c,
                                        const SegmenterParams& params) {
    const auto& contour = cluster.contour_px;
    const auto& d = cluster.distance_px;
    const int n = static_cast<int>(contour.size());
    const auto& cuts = c.cuts;
    std::vector<BladeContour> pieces;
    for (size_t k = 0; k < cuts.size(); ++k) {
        const int start = cuts[k].first;
        const int length =
            cuts.size() == 1 ? n : wrap(cuts[(k + 1) % cuts.size()].first - start, n);
        BladeContour blade;
        blade.contour_px.reserve(static_cast<size_t>(length) + 1);
        float best = -1.f;
        for (int s = 0; s <= length && s < n; ++s) {  // one cut: the whole contour once
            const int i = wrap(start + s, n);
            blade.contour_px.push_back(contour[static_cast<size_t>(i)]);
            if (d[static_cast<size_t>(i)] > best) {
                best = d[static_cast<size_t>(i)];
                blade.tipIndex = s;
            }
        }
        // A minimum too shallow to cut but deep inside the piece: two tips, perhaps two
        // blades that touch along their length (merged into one piece).
        float secondDip_px = 0.f;
        for (const auto& m : c.minima)
            if (m.second < c.threshold && wrap(m.first - start, n) > 0 &&
                wrap(m.first - start, n) < length)
                secondDip_px = std::max(secondDip_px, m.second);
        if (params.secondTipFraction > 0.f &&
            secondDip_px >= params.secondTipFraction * c.threshold)
            addFlag(blade, BladeFlag::Overlapping,
                    "its contour dips " + std::to_string(secondDip_px).substr(0, 4) +
                        " px between two tips (cuts need " +
                        std::to_string(c.threshold).substr(0, 4) +
                        " px): it may hold blades that touch");
        pieces.push_back(std::move(blade));
    }
    return pieces;
}

// With BladeMaskMethod::Wedge: a pixel inside exactly one blade's wedge (its piece closed
// through the base point) goes to that blade (`owner`: blade index + 1, box coordinates); the
// fork zone is then re-decided by centre lines and depth (fork_partition.cpp).
void assignWedges(const std::vector<BladeContour>& pieces, const BladeCluster& cluster,
                  const cv::Rect& box, const cv::Mat1b& region, const cv::Mat1w& depth_mm,
                  float raggedness, const SegmenterParams& params, cv::Mat1i& owner,
                  StageReport& report) {
    const cv::Point base(cvRound(cluster.reference_px.x) - box.x,
                         cvRound(cluster.reference_px.y) - box.y);
    cv::Mat1b covering(box.size(), std::uint8_t{0});  // wedges over a pixel (saturating)
    cv::Mat1i wedgeOwner(box.size(), 0);
    const cv::Rect inBox({0, 0}, box.size());
    for (size_t k = 0; k < pieces.size(); ++k) {
        std::vector<cv::Point> polygon;
        for (const auto& p : pieces[k].contour_px) polygon.push_back(p - box.tl());
        polygon.push_back(base);
        // Each wedge is filled over its own bounding box only: a dozen of them over the
        // whole cluster box cost more than the rest of the partition.
        const cv::Rect wedgeBox = cv::boundingRect(polygon) & inBox;
        if (wedgeBox.empty()) continue;
        cv::Mat1b wedge(wedgeBox.size(), std::uint8_t{0});
        cv::fillPoly(wedge, std::vector<std::vector<cv::Point>>{polygon}, 255, cv::LINE_8, 0,
                     -wedgeBox.tl());
        cv::Mat1b coveringHere = covering(wedgeBox);
        cv::add(coveringHere, 1, coveringHere, wedge);
        wedgeOwner(wedgeBox).setTo(static_cast<int>(k) + 1, wedge);
    }
    for (int y = 0; y < region.rows; ++y)
        for (int x = 0; x < region.cols; ++x)
            if (region(y, x) && covering(y, x) == 1) owner(y, x) = wedgeOwner(y, x);
    if (params.forkByDepth && !depth_mm.empty() && raggedness <= params.forkMaxRaggedness) {
        const int changed =
            assignForkZone(pieces, box.tl(), cluster.reference_px - cv::Point2f(box.tl()), region,
                           depth_mm, params.forkDepthSigma_mm, owner);
        report.notes.push_back("fork zone: " + std::to_string(changed) +
                               " px given to another blade by centre lines and depth");
    }
}

// Every region pixel still without a blade goes to the nearest contour piece. The distance
// transform is the costliest step of the partition, so it runs only when some pixel is left,
// and only over the part of the box that holds every such pixel's nearest contour point.
void assignNearestPiece(const std::vector<BladeContour>& pieces, const cv::Rect& box,
                        const cv::Mat1b& region, cv::Mat1i& owner) {
    cv::Rect left;  // pixels still without a blade
    int reach = 0;  // bound on their distance to the nearest contour point
    for (int y = 0; y < region.rows; ++y)
        for (int x = 0; x < region.cols; ++x)
            if (region(y, x) && owner(y, x) == 0) {
                left |= cv::Rect(x, y, 1, 1);
                // A row or column through the pixel meets the 8-connected outer contour before
                // it leaves the box, so the nearest contour point is no farther than the
                // nearest box edge.
                reach = std::max(reach, std::min({x, y, box.width - 1 - x, box.height - 1 - y}));
            }
    if (left.empty()) return;
    // Its chamfer metric departs from the Euclidean by a few percent, hence the margin.
    const int grow = reach + reach / kChamferMarginDivisor + 2;
    const cv::Rect sub = grownWithin(left, grow, cv::Rect({0, 0}, box.size()));
    cv::Mat1b seeds(sub.size(), std::uint8_t{255});
    cv::Mat1i seedBlade(sub.size(), 0);
    for (size_t k = 0; k < pieces.size(); ++k)
        for (const auto& p : pieces[k].contour_px) {
            const cv::Point q = p - box.tl() - sub.tl();
            if (q.x < 0 || q.y < 0 || q.x >= sub.width || q.y >= sub.height) continue;
            seeds(q) = 0;
            seedBlade(q) = static_cast<int>(k) + 1;
        }
    // DIST_LABEL_PIXEL numbers the zero pixels 1, 2, ... in row-major order.
    std::vector<int> bladeOfLabel{0};
    for (int y = 0; y < seeds.rows; ++y)
        for (int x = 0; x < seeds.cols; ++x)
            if (seeds(y, x) == 0) bladeOfLabel.push_back(seedBlade(y, x));
    cv::Mat1f dist;
    cv::Mat1i labels;
    cv::distanceTransform(seeds, dist, labels, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
    for (int y = left.y; y < left.br().y; ++y)
        for (int x = left.x; x < left.br().x; ++x) {
            if (!region(y, x) || owner(y, x) != 0) continue;
            const int l = labels(y - sub.y, x - sub.x);
            if (l > 0 && l < static_cast<int>(bladeOfLabel.size()))
                owner(y, x) = bladeOfLabel[static_cast<size_t>(l)];
        }
}

// The pieces as blades, each with the mask of the pixels it owns over its own bounding box
// (BladeContour::maskOrigin_px); a piece that owns none is dropped.
std::vector<BladeContour> bladesOwning(std::vector<BladeContour> pieces, const cv::Mat1i& owner,
                                       cv::Point origin, int firstId, StageReport& report) {
    std::vector<cv::Rect> bladeBox(pieces.size());
    for (int y = 0; y < owner.rows; ++y)
        for (int x = 0; x < owner.cols; ++x)
            if (const int k = owner(y, x); k > 0)
                bladeBox[static_cast<size_t>(k - 1)] |= {x, y, 1, 1};
    std::vector<cv::Mat1b> ownMasks(pieces.size());
    for (size_t k = 0; k < pieces.size(); ++k) ownMasks[k] = cv::Mat1b::zeros(bladeBox[k].size());
    for (int y = 0; y < owner.rows; ++y)
        for (int x = 0; x < owner.cols; ++x)
            if (const int k = owner(y, x); k > 0) {
                const cv::Rect& b = bladeBox[static_cast<size_t>(k - 1)];
                ownMasks[static_cast<size_t>(k - 1)](y - b.y, x - b.x) = 255;
            }
    std::vector<BladeContour> blades;
    int empty = 0;
    for (size_t k = 0; k < pieces.size(); ++k) {
        if (bladeBox[k].empty()) {
            ++empty;
            continue;
        }
        BladeContour blade = std::move(pieces[k]);
        blade.mask = ownMasks[k];
        blade.maskOrigin_px = origin + bladeBox[k].tl();
        blade.id = firstId + static_cast<int>(blades.size());
        blades.push_back(std::move(blade));
    }
    if (empty > 0)
        report.notes.push_back(std::to_string(empty) +
                               " contour piece(s) enclose no pixels: dropped");
    return blades;
}

}  // namespace

std::vector<BladeContour> partitionCluster(BladeCluster& cluster, const cv::Mat1b& mask,
                                           const cv::Mat1w& depth_mm, float raggedness,
                                           const SegmenterParams& params, int firstId,
                                           StageReport& report) {
    const Cuts cuts = persistentCuts(cluster, params, report);
    std::vector<BladeContour> pieces = contourPieces(cluster, cuts, params);
    cv::Rect box;
    const cv::Mat1b region = clusterRegion(cluster, mask, box);
    // Masks. Every cluster pixel goes to the blade whose contour piece is nearest: a Voronoi
    // split of the cluster by contour pieces (cv::distanceTransform with per-pixel labels). That
    // hands the shared base, below the forks, to the two outermost blades, whose pieces enclose
    // it; with the Wedge method a pixel inside exactly one blade's wedge goes to that blade
    // instead, and only pixels in no wedge or in several (a contour not star-shaped about the
    // base) fall back.
    cv::Mat1i owner(box.size(), 0);  // blade index + 1
    if (pieces.size() == 1) owner.setTo(1, region);
    if (params.bladeMask == BladeMaskMethod::Wedge &&
        params.reference == ReferencePoint::BasePoint && pieces.size() > 1)
        assignWedges(pieces, cluster, box, region, depth_mm, raggedness, params, owner, report);
    assignNearestPiece(pieces, box, region, owner);
    return bladesOwning(std::move(pieces), owner, box.tl(), firstId, report);
}

}  // namespace meadow::capture::segmentation
