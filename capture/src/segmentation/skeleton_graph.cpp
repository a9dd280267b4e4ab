// A one-pixel skeleton as nodes (tips, junctions, the root) and the paths between them.
#include "segmentation/skeleton_graph.h"

#include <algorithm>
#include <deque>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <set>
#include <utility>

namespace meadow::capture::segmentation {

namespace {

constexpr int kNone = -1;
constexpr int kCrossingEnds = 4;  // two leaves crossing
const cv::Point kNeighbours[8] = {{0, -1},  {-1, 0}, {1, 0},  {0, 1},
                                  {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};

bool inside(const cv::Mat& m, cv::Point p) {
    return p.x >= 0 && p.y >= 0 && p.x < m.cols && p.y < m.rows;
}

int neighbourCount(const cv::Mat1b& skeleton, cv::Point p) {
    int n = 0;
    for (const cv::Point& d : kNeighbours) n += inside(skeleton, p + d) && skeleton(p + d);
    return n;
}

cv::Point2f centreOf(const std::vector<cv::Point>& pixels) {
    cv::Point2f c(0.f, 0.f);
    for (const cv::Point& p : pixels) c += cv::Point2f(p);
    return c * (1.f / static_cast<float>(std::max<std::size_t>(1, pixels.size())));
}

// The shortest 8-connected path within `component` (pixels labelled `label`) from `from` to
// `to`, both included; a kink's extra pixel stays off it.
std::vector<cv::Point> shortestPath(const cv::Mat1i& component, int label, cv::Point from,
                                    cv::Point to) {
    cv::Mat1i previous(component.size(), kNone);
    std::deque<cv::Point> queue{from};
    previous(from) = from.y * component.cols + from.x;
    while (!queue.empty() && previous(to) == kNone) {
        const cv::Point p = queue.front();
        queue.pop_front();
        for (const cv::Point& d : kNeighbours) {
            const cv::Point q = p + d;
            if (!inside(component, q) || component(q) != label || previous(q) != kNone) continue;
            previous(q) = p.y * component.cols + p.x;
            queue.push_back(q);
        }
    }
    std::vector<cv::Point> path;
    if (previous(to) == kNone) return path;
    for (cv::Point p = to;;) {
        path.push_back(p);
        if (p == from) break;
        const int i = previous(p);
        p = {i % component.cols, i / component.cols};
    }
    std::reverse(path.begin(), path.end());
    return path;
}

// A node that one edge or none meets is a free end, even where the skeleton's last pixels touch
// (a blob of junction pixels at a leaf's tip).
void markFreeEnds(SkeletonGraph& graph) {
    for (auto& node : graph.nodes) node.tip = !node.root && node.ends.size() <= 1;
}

// The graph with every pixel of `notJunction` taken as a path's pixel, whatever its neighbours.
SkeletonGraph buildGraph(const cv::Mat1b& skeleton, cv::Point root, const cv::Mat1b& notJunction) {
    SkeletonGraph graph;
    // The skeleton is a few percent of its box: every pass below walks its pixels (in row order,
    // as a scan of the box would meet them), not the box.
    std::vector<cv::Point> onSkeleton;
    cv::findNonZero(skeleton, onSkeleton);
    cv::Mat1i nodeOf(skeleton.size(), kNone);
    // Junction pixels, touching ones as one node.
    cv::Mat1b junction(skeleton.size(), std::uint8_t{0});
    for (const cv::Point& p : onSkeleton)
        if (!notJunction(p) && neighbourCount(skeleton, p) >= 3) junction(p) = 255;
    cv::Mat1i junctionLabel;
    const int junctions = cv::connectedComponents(junction, junctionLabel, 8, CV_32S);
    graph.nodes.resize(static_cast<std::size_t>(std::max(0, junctions - 1)));
    for (const cv::Point& p : onSkeleton)
        if (const int j = junctionLabel(p); j > 0) {
            graph.nodes[static_cast<std::size_t>(j - 1)].pixels.push_back(p);
            nodeOf(p) = j - 1;
        }
    // Tips (and lone pixels), and the root where it is on a path.
    for (const cv::Point& p : onSkeleton) {
        if (nodeOf(p) != kNone) continue;
        const int n = neighbourCount(skeleton, p);
        if (n >= 2 && p != root) continue;
        SkeletonNode node;
        node.pixels = {p};
        node.tip = n <= 1;
        nodeOf(p) = static_cast<int>(graph.nodes.size());
        graph.nodes.push_back(std::move(node));
    }
    for (auto& node : graph.nodes) node.centre = centreOf(node.pixels);
    if (inside(skeleton, root) && nodeOf(root) != kNone) {
        graph.rootNode = nodeOf(root);
        graph.nodes[static_cast<std::size_t>(graph.rootNode)].root = true;
    }

    // Edges: each connected run of path pixels (no node's) joins the nodes it touches; nodes
    // that touch each other are joined by an empty edge.
    const auto addEdge = [&](SkeletonEdge edge) {
        const int e = static_cast<int>(graph.edges.size());
        graph.nodes[static_cast<std::size_t>(edge.from)].ends.push_back(2 * e);
        graph.nodes[static_cast<std::size_t>(edge.to)].ends.push_back(2 * e + 1);
        graph.edges.push_back(std::move(edge));
    };
    std::set<std::pair<int, int>> touching;
    cv::Mat1b onPath(skeleton.size(), std::uint8_t{0});
    for (const cv::Point& p : onSkeleton) {
        if (nodeOf(p) == kNone) {
            onPath(p) = 255;
            continue;
        }
        for (const cv::Point& d : kNeighbours) {
            const cv::Point q = p + d;
            if (!inside(skeleton, q) || !skeleton(q)) continue;
            const int a = nodeOf(p), b = nodeOf(q);
            if (b != kNone && a != b && touching.insert(std::minmax(a, b)).second)
                addEdge({{}, a, b});
        }
    }
    cv::Mat1i run;
    const int runs = cv::connectedComponents(onPath, run, 8, CV_32S);
    // Where each run touches each node: (node, the run's pixel beside it), the first seen.
    std::vector<std::vector<std::pair<int, cv::Point>>> touches(static_cast<std::size_t>(runs));
    std::vector<std::vector<cv::Point>> runPixels(static_cast<std::size_t>(runs));
    for (const cv::Point& p : onSkeleton) {
        const int r = run(p);
        if (r == 0) continue;
        runPixels[static_cast<std::size_t>(r)].push_back(p);
        auto& t = touches[static_cast<std::size_t>(r)];
        for (const cv::Point& d : kNeighbours) {
            const cv::Point q = p + d;
            if (!inside(skeleton, q) || nodeOf(q) == kNone) continue;
            const bool known = std::any_of(t.begin(), t.end(), [&](const auto& nt) {
                return nt.first == nodeOf(q) && cv::norm(nt.second - p) < 3.0;
            });
            if (!known) t.emplace_back(nodeOf(q), p);
        }
    }
    for (int r = 1; r < runs; ++r) {
        const auto& t = touches[static_cast<std::size_t>(r)];
        if (t.size() < 2) continue;  // a ring of path pixels that touches no node
        // The two touches farthest apart along the run: its two ends.
        std::size_t a = 0, b = 1;
        double best = -1.0;
        for (std::size_t i = 0; i < t.size(); ++i)
            for (std::size_t j = i + 1; j < t.size(); ++j)
                if (const double d = cv::norm(t[i].second - t[j].second);
                    d > best && (t[i].first != t[j].first || d >= 2.0))
                    best = d, a = i, b = j;
        if (best < 0.0) continue;
        SkeletonEdge edge;
        edge.from = t[a].first;
        edge.to = t[b].first;
        const cv::Rect within = cv::boundingRect(runPixels[static_cast<std::size_t>(r)]);
        edge.pixels =
            shortestPath(run(within), r, t[a].second - within.tl(), t[b].second - within.tl());
        for (cv::Point& p : edge.pixels) p += within.tl();
        if (edge.pixels.empty()) continue;
        addEdge(std::move(edge));
    }
    markFreeEnds(graph);
    return graph;
}

}  // namespace

SkeletonGraph skeletonGraph(const cv::Mat1b& skeleton, cv::Point root) {
    // A "junction" that only two paths leave is a kink of the thinning (a staircase step), not a
    // junction: built again as part of the path, so that its edge is read as one.
    cv::Mat1b kinks(skeleton.size(), std::uint8_t{0});
    SkeletonGraph graph = buildGraph(skeleton, root, kinks);
    bool any = false;
    for (const SkeletonNode& node : graph.nodes)
        if (!node.root && !node.tip && node.ends.size() == 2 &&
            node.ends[0] / 2 != node.ends[1] / 2)
            for (const cv::Point& p : node.pixels) kinks(p) = 255, any = true;
    return any ? buildGraph(skeleton, root, kinks) : graph;
}

int removeSpurs(cv::Mat1b& skeleton, cv::Point root, float minLength_px) {
    int removed = 0;
    for (bool again = true; again;) {
        again = false;
        const SkeletonGraph graph = skeletonGraph(skeleton, root);
        for (const SkeletonEdge& edge : graph.edges) {
            const SkeletonNode& a = graph.nodes[static_cast<std::size_t>(edge.from)];
            const SkeletonNode& b = graph.nodes[static_cast<std::size_t>(edge.to)];
            const bool aSpur = a.tip && !a.root && b.ends.size() >= 3;
            const bool bSpur = b.tip && !b.root && a.ends.size() >= 3;
            if (!(aSpur || bSpur) || static_cast<float>(edge.pixels.size() + 1) >= minLength_px)
                continue;
            for (const cv::Point& p : edge.pixels) skeleton(p) = 0;
            skeleton((aSpur ? a : b).pixels.front()) = 0;
            ++removed;
            again = true;
        }
    }
    return removed;
}

void mergeCloseJunctions(SkeletonGraph& graph, const cv::Mat1f& halfWidth_px) {
    // The root merges too: a junction beside where the plant stands is where it stands.
    const auto isJunction = [&](int n) {
        const SkeletonNode& node = graph.nodes[static_cast<std::size_t>(n)];
        return node.root || (!node.tip && node.ends.size() >= 3);
    };
    const auto widthAt = [&](int n) {
        float w = 0.f;
        for (const cv::Point& p : graph.nodes[static_cast<std::size_t>(n)].pixels)
            w = std::max(w, 2.f * halfWidth_px(p));
        return w;
    };
    std::vector<int> parent(graph.nodes.size());
    std::iota(parent.begin(), parent.end(), 0);
    const auto find = [&](int n) {
        while (parent[static_cast<std::size_t>(n)] != n)
            n = parent[static_cast<std::size_t>(n)] =
                parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(n)])];
        return n;
    };
    // One crossing is what a merged junction may hold: no wider than the mask there, or two
    // leaves crossing at a sharp angle (four edges leave it, over a span the crossing draws
    // out). Junctions chained up a broad stem, each a short bridge from the next (leaves leave
    // it every few cm), would make one node the length of the stem with every leaf leaving it
    // at the plant's foot; they stay apart. Where the plant stands, a pot's rim and the stem's
    // foot thin into a tangle wider than the stem: all of it is the root.
    std::vector<std::vector<int>> members(graph.nodes.size());
    std::vector<int> ends(graph.nodes.size());
    for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
        members[n] = {static_cast<int>(n)};
        ends[n] = static_cast<int>(graph.nodes[n].ends.size());
    }
    const auto withinWidth = [&](int a, int b) {
        const auto& ma = members[static_cast<std::size_t>(a)];
        const auto& mb = members[static_cast<std::size_t>(b)];
        float width = 0.f, span = 0.f;
        for (const auto* set : {&ma, &mb})
            for (const int m : *set) width = std::max(width, widthAt(m));
        for (const int i : ma)
            for (const int j : mb)
                span = std::max(
                    span,
                    static_cast<float>(cv::norm(graph.nodes[static_cast<std::size_t>(i)].centre -
                                                graph.nodes[static_cast<std::size_t>(j)].centre)));
        return span < width;
    };
    std::vector<bool> absorbed(graph.edges.size(), false);
    // Merges the junctions edge `e` bridges, if it is short; `atRoot`: only where one of them is
    // (in) the root, else only where neither is. Returns whether it merged.
    const auto merge = [&](std::size_t e, bool atRoot) {
        const SkeletonEdge& edge = graph.edges[e];
        if (absorbed[e] || edge.from == edge.to || !isJunction(edge.from) || !isJunction(edge.to))
            return false;
        const float bridge = static_cast<float>(edge.pixels.size() + 1);
        if (bridge >= std::max(widthAt(edge.from), widthAt(edge.to))) return false;
        const int a = find(edge.from), b = find(edge.to);
        const int root = graph.rootNode == kNone ? kNone : find(graph.rootNode);
        if (a == b || atRoot != (a == root || b == root)) return false;
        const int endsMerged =
            ends[static_cast<std::size_t>(a)] + ends[static_cast<std::size_t>(b)] - 2;
        if (!atRoot && endsMerged > kCrossingEnds && !withinWidth(a, b)) return false;
        parent[static_cast<std::size_t>(b)] = a;
        ends[static_cast<std::size_t>(a)] = endsMerged;
        auto& into = members[static_cast<std::size_t>(a)];
        auto& from = members[static_cast<std::size_t>(b)];
        into.insert(into.end(), from.begin(), from.end());
        from.clear();
        absorbed[e] = true;
        return true;
    };
    // The root's tangle first, until no short bridge leaves it (whatever the edges' order), then
    // the crossings.
    for (bool grew = true; grew;) {
        grew = false;
        for (std::size_t e = 0; e < graph.edges.size(); ++e) grew = merge(e, true) || grew;
    }
    for (std::size_t e = 0; e < graph.edges.size(); ++e) merge(e, false);
    if (std::none_of(absorbed.begin(), absorbed.end(), [](bool x) { return x; })) return;

    // Rebuild: one node per set, the bridges' pixels part of it, the other edges renumbered.
    SkeletonGraph merged;
    std::vector<int> newNode(graph.nodes.size(), kNone);
    for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
        const int r = find(static_cast<int>(n));
        if (newNode[static_cast<std::size_t>(r)] == kNone) {
            newNode[static_cast<std::size_t>(r)] = static_cast<int>(merged.nodes.size());
            merged.nodes.emplace_back();
        }
        SkeletonNode& into =
            merged.nodes[static_cast<std::size_t>(newNode[static_cast<std::size_t>(r)])];
        const SkeletonNode& node = graph.nodes[n];
        into.pixels.insert(into.pixels.end(), node.pixels.begin(), node.pixels.end());
        into.tip = into.tip || node.tip;
        into.root = into.root || node.root;
    }
    for (std::size_t n = 0; n < graph.nodes.size(); ++n)
        newNode[n] = newNode[static_cast<std::size_t>(find(static_cast<int>(n)))];
    for (std::size_t e = 0; e < graph.edges.size(); ++e) {
        SkeletonEdge edge = std::move(graph.edges[e]);
        edge.from = newNode[static_cast<std::size_t>(edge.from)];
        edge.to = newNode[static_cast<std::size_t>(edge.to)];
        if (absorbed[e]) {
            auto& pixels = merged.nodes[static_cast<std::size_t>(edge.from)].pixels;
            pixels.insert(pixels.end(), edge.pixels.begin(), edge.pixels.end());
            continue;
        }
        const int index = static_cast<int>(merged.edges.size());
        merged.nodes[static_cast<std::size_t>(edge.from)].ends.push_back(2 * index);
        merged.nodes[static_cast<std::size_t>(edge.to)].ends.push_back(2 * index + 1);
        merged.edges.push_back(std::move(edge));
    }
    for (auto& node : merged.nodes) node.centre = centreOf(node.pixels);
    markFreeEnds(merged);
    merged.rootNode =
        graph.rootNode == kNone ? kNone : newNode[static_cast<std::size_t>(graph.rootNode)];
    graph = std::move(merged);
}

}  // namespace meadow::capture::segmentation
