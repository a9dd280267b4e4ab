// The skeleton's edges joined through its junctions by the smoothest continuation in direction
// and depth: one strand per leaf (or stem), however many leaves cross it.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "segmentation/skeleton_graph.h"

namespace meadow::capture::segmentation {

namespace {

constexpr int kNone = -1;
constexpr int kMinDirectionPixels = 8;  // read a direction over at least this many pixels

// An edge's pixels in order away from the node at its end `side` (0: from, 1: to).
std::vector<cv::Point> awayFrom(const SkeletonEdge& edge, int side) {
    std::vector<cv::Point> p = edge.pixels;
    if (side == 1) std::reverse(p.begin(), p.end());
    return p;
}

// How an edge leaves a junction: its direction beyond the junction's own bend, and its depth
// carried back to the junction (0 where too few readings).
struct Departure {
    cv::Point2f direction;
    float depthAtJunction_mm = 0.f;
};

// The depth a run of readings along an edge would have at the junction: the medians of its near
// and far halves give a slope, carried back over the distance from the junction.
float depthCarriedBack(const std::vector<std::pair<float, float>>& arcAndDepth) {
    if (arcAndDepth.size() < 4) return 0.f;
    const std::size_t half = arcAndDepth.size() / 2;
    const auto medianOf = [](std::vector<float> v) {
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    std::vector<float> nearArc, nearZ, farArc, farZ;
    for (std::size_t i = 0; i < arcAndDepth.size(); ++i) {
        (i < half ? nearArc : farArc).push_back(arcAndDepth[i].first);
        (i < half ? nearZ : farZ).push_back(arcAndDepth[i].second);
    }
    const float a0 = medianOf(nearArc), z0 = medianOf(nearZ);
    const float a1 = medianOf(farArc), z1 = medianOf(farZ);
    const float slope = a1 > a0 ? (z1 - z0) / (a1 - a0) : 0.f;
    return z0 - slope * a0;
}

Departure departure(const SkeletonGraph& graph, int end, const cv::Mat1f& halfWidth_px,
                    const cv::Mat1w& depth_mm) {
    const SkeletonEdge& edge = graph.edges[static_cast<std::size_t>(end / 2)];
    const int side = end % 2;
    const SkeletonNode& here =
        graph.nodes[static_cast<std::size_t>(side == 0 ? edge.from : edge.to)];
    const SkeletonNode& there =
        graph.nodes[static_cast<std::size_t>(side == 0 ? edge.to : edge.from)];
    const std::vector<cv::Point> away = awayFrom(edge, side);
    float reach = 0.f;  // the junction's own bend reaches about its half width
    for (const cv::Point& p : here.pixels) reach = std::max(reach, halfWidth_px(p));
    const auto skip = static_cast<std::size_t>(std::lround(reach));
    const std::size_t stop =
        skip + static_cast<std::size_t>(std::max<float>(kMinDirectionPixels, 2.f * reach));
    Departure d;
    if (away.size() < skip + 3) {  // a short edge: the straight line to its other node
        d.direction = there.centre - here.centre;
    } else {
        std::vector<cv::Point2f> run;
        for (std::size_t i = skip; i < std::min(stop, away.size()); ++i)
            run.push_back(cv::Point2f(away[i]));
        cv::Vec4f line;
        cv::fitLine(run, line, cv::DIST_L2, 0, 0.01, 0.01);
        d.direction = {line[0], line[1]};
        if (d.direction.dot(run.back() - here.centre) < 0.f) d.direction = -d.direction;
    }
    const float n = std::hypot(d.direction.x, d.direction.y);
    d.direction = n > 0.f ? d.direction * (1.f / n) : cv::Point2f(0.f, 0.f);
    if (!depth_mm.empty()) {
        std::vector<std::pair<float, float>> readings;
        for (std::size_t i = skip; i < std::min(stop, away.size()); ++i)
            if (const std::uint16_t z = depth_mm(away[i]); z > 0)
                readings.emplace_back(static_cast<float>(i + 1), static_cast<float>(z));
        d.depthAtJunction_mm = depthCarriedBack(readings);
    }
    return d;
}

// How far one edge turns into another through a junction, in degrees: 0 for a straight line.
float bendThrough_deg(const Departure& a, const Departure& b) {
    const float straight = -a.direction.dot(b.direction);  // cos of the angle a -> b turns by
    return std::acos(std::clamp(straight, -1.f, 1.f)) * 180.f / std::numbers::pi_v<float>;
}

}  // namespace

std::vector<cv::Point> Strand::path(const SkeletonGraph& graph) const {
    std::vector<cv::Point> out;
    const auto nearestPixel = [&](int node, cv::Point2f to) {
        const auto& px = graph.nodes[static_cast<std::size_t>(node)].pixels;
        return *std::min_element(px.begin(), px.end(), [&](cv::Point a, cv::Point b) {
            return cv::norm(cv::Point2f(a) - to) < cv::norm(cv::Point2f(b) - to);
        });
    };
    for (std::size_t i = 0; i < edges.size(); ++i) {
        const SkeletonEdge& edge = graph.edges[static_cast<std::size_t>(edges[i])];
        std::vector<cv::Point> p = awayFrom(edge, forward[i] ? 0 : 1);
        const int first = forward[i] ? edge.from : edge.to;
        const int last = forward[i] ? edge.to : edge.from;
        const cv::Point2f towards =
            p.empty() ? graph.nodes[static_cast<std::size_t>(last)].centre : cv::Point2f(p.front());
        if (i == 0 || out.empty()) out.push_back(nearestPixel(first, towards));
        out.insert(out.end(), p.begin(), p.end());
        out.push_back(nearestPixel(last, out.back()));
    }
    return out;
}

Strands followStrands(const SkeletonGraph& graph, const cv::Mat1f& halfWidth_px,
                      const cv::Mat1w& depth_mm, const StrandParams& params) {
    Strands out;
    std::vector<int> partner(2 * graph.edges.size(), kNone);  // the end each end is joined to
    for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
        const SkeletonNode& node = graph.nodes[n];
        if (node.root || node.ends.size() < 2) continue;
        if (node.ends.size() == 2) {  // no choice: a path through a junction's leftover pixel
            partner[static_cast<std::size_t>(node.ends[0])] = node.ends[1];
            partner[static_cast<std::size_t>(node.ends[1])] = node.ends[0];
            continue;
        }
        std::vector<Departure> leaving;
        for (const int end : node.ends)
            leaving.push_back(departure(graph, end, halfWidth_px, depth_mm));
        struct Candidate {
            float bend_deg;
            std::size_t a, b;
        };
        std::vector<Candidate> candidates;
        for (std::size_t a = 0; a < leaving.size(); ++a)
            for (std::size_t b = a + 1; b < leaving.size(); ++b) {
                if (node.ends[a] / 2 == node.ends[b] / 2) continue;  // a loop's own two ends
                const float bend = bendThrough_deg(leaving[a], leaving[b]);
                const float za = leaving[a].depthAtJunction_mm, zb = leaving[b].depthAtJunction_mm;
                const bool depthBreaks =
                    za > 0.f && zb > 0.f && std::abs(za - zb) > params.maxDepthStep_mm;
                if (bend < params.maxBend_deg && !depthBreaks) candidates.push_back({bend, a, b});
            }
        std::sort(candidates.begin(), candidates.end(),
                  [](const Candidate& x, const Candidate& y) { return x.bend_deg < y.bend_deg; });
        std::vector<bool> taken(leaving.size(), false);
        for (const Candidate& c : candidates) {
            if (taken[c.a] || taken[c.b]) continue;
            taken[c.a] = taken[c.b] = true;
            partner[static_cast<std::size_t>(node.ends[c.a])] = node.ends[c.b];
            partner[static_cast<std::size_t>(node.ends[c.b])] = node.ends[c.a];
        }
    }

    // Walk the chains: from every unjoined end first (open strands), then what is left (loops).
    out.strandOfEdge.assign(graph.edges.size(), kNone);
    const auto nodeAt = [&](int end) {
        const SkeletonEdge& e = graph.edges[static_cast<std::size_t>(end / 2)];
        return end % 2 == 0 ? e.from : e.to;
    };
    const auto walk = [&](int startEnd) {
        Strand s;
        s.startNode = nodeAt(startEnd);
        for (int end = startEnd;;) {
            const int edge = end / 2;
            if (out.strandOfEdge[static_cast<std::size_t>(edge)] != kNone) break;
            out.strandOfEdge[static_cast<std::size_t>(edge)] = static_cast<int>(out.strands.size());
            s.edges.push_back(edge);
            s.forward.push_back(end % 2 == 0);
            const int other = end ^ 1;  // the edge's far end
            s.endNode = nodeAt(other);
            const int next = partner[static_cast<std::size_t>(other)];
            if (next == kNone || out.strandOfEdge[static_cast<std::size_t>(next / 2)] != kNone)
                break;
            s.through.push_back(s.endNode);
            end = next;
        }
        out.strands.push_back(std::move(s));
    };
    for (int end = 0; end < static_cast<int>(partner.size()); ++end)
        if (partner[static_cast<std::size_t>(end)] == kNone &&
            out.strandOfEdge[static_cast<std::size_t>(end / 2)] == kNone)
            walk(end);
    for (int end = 0; end < static_cast<int>(partner.size()); end += 2)
        if (out.strandOfEdge[static_cast<std::size_t>(end / 2)] == kNone) walk(end);
    return out;
}

}  // namespace meadow::capture::segmentation
