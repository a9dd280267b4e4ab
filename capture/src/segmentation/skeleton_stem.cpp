// The stem among the skeleton's strands: from where the plant stands, along the strands that
// carry the most leaves, to the highest node a leaf leaves it at.
#include <algorithm>

#include "segmentation/skeleton_graph.h"

namespace meadow::capture::segmentation {

namespace {

constexpr int kNone = -1;

void reverseStrand(Strand& s) {
    std::reverse(s.edges.begin(), s.edges.end());
    std::reverse(s.forward.begin(), s.forward.end());
    s.forward.flip();
    std::reverse(s.through.begin(), s.through.end());
    std::swap(s.startNode, s.endNode);
}

// The j-th node along a strand: its start, the nodes it runs through, its end.
int nodeAlong(const Strand& s, std::size_t j) {
    if (j == 0) return s.startNode;
    return j <= s.through.size() ? s.through[j - 1] : s.endNode;
}

// How many strands meet each node that is not a free tip: those that end there and, with
// `throughToo`, those that run through it (a leaf pair leaving a node on both sides lines up as
// one strand through it).
std::vector<int> strandsMeeting(const SkeletonGraph& graph, const Strands& strands,
                                bool throughToo) {
    std::vector<int> count(graph.nodes.size(), 0);
    for (const Strand& s : strands.strands) {
        for (const int n : {s.startNode, s.endNode})
            if (!graph.nodes[static_cast<std::size_t>(n)].tip) ++count[static_cast<std::size_t>(n)];
        if (throughToo)
            for (const int n : s.through) ++count[static_cast<std::size_t>(n)];
    }
    return count;
}

// Other strands meeting `s` beyond its j-th node: the leaves it carries further on. `self` is
// what `s` itself adds to `meeting` at a node it runs through (1 when that counts strands
// through, else 0).
int leavesBeyond(const SkeletonGraph& graph, const std::vector<int>& meeting, const Strand& s,
                 std::size_t j, int self = 1) {
    int count = 0;
    for (std::size_t m = j + 1; m < s.edges.size(); ++m)
        count += meeting[static_cast<std::size_t>(nodeAlong(s, m))] - self;
    if (s.endNode != graph.rootNode && !graph.nodes[static_cast<std::size_t>(s.endNode)].tip)
        count += meeting[static_cast<std::size_t>(s.endNode)] - 1;  // not its own end
    return count;
}

// Moves what strand `i` runs on beyond its first `keep` edges into a new strand.
void splitOff(Strands& strands, std::size_t i, std::size_t keep) {
    Strand rest;
    {
        Strand& s = strands.strands[i];
        rest.startNode = s.through[keep - 1];
        rest.endNode = s.endNode;
        const auto k = static_cast<std::ptrdiff_t>(keep);
        rest.edges.assign(s.edges.begin() + k, s.edges.end());
        rest.forward.assign(s.forward.begin() + k, s.forward.end());
        rest.through.assign(s.through.begin() + k, s.through.end());
        s.edges.resize(keep);
        s.forward.resize(keep);
        s.endNode = rest.startNode;
        s.through.resize(keep - 1);
    }
    for (const int e : rest.edges)
        strands.strandOfEdge[static_cast<std::size_t>(e)] =
            static_cast<int>(strands.strands.size());
    strands.strands.push_back(std::move(rest));
}

}  // namespace

std::vector<int> followStem(const SkeletonGraph& graph, Strands& strands) {
    std::vector<int> meeting = strandsMeeting(graph, strands, true);
    const std::vector<int> ending = strandsMeeting(graph, strands, false);
    // The first piece: of the strands leaving the root that a leaf leaves (ends on), the one
    // that carries the most leaves. Leaves that only cross the strands from the root make no
    // stem: two blades crossing over a shared base do not.
    int current = kNone, most = 0;
    for (std::size_t i = 0; i < strands.strands.size(); ++i) {
        Strand& s = strands.strands[i];
        if (s.startNode != graph.rootNode && s.endNode != graph.rootNode) continue;
        if (s.startNode != graph.rootNode) reverseStrand(s);
        if (leavesBeyond(graph, ending, s, 0, 0) == 0) continue;
        if (const int n = leavesBeyond(graph, meeting, s, 0); n > most)
            current = static_cast<int>(i), most = n;
    }
    if (current == kNone) return {};
    std::vector<int> stem{current};
    // Up the stem: where a strand that ends on it carries more leaves beyond that node than the
    // stem's own continuation does, the stem turns into it (a leaf ran on more smoothly there
    // than the stem did), and what it leaves is a leaf leaving there.
    for (bool turned = true; turned;) {
        turned = false;
        const Strand& s = strands.strands[static_cast<std::size_t>(current)];
        // At its nodes, and at its end where that meets other strands (s dangles once turned).
        for (std::size_t j = 1; !turned && j <= s.edges.size(); ++j) {
            const bool atEnd = j == s.edges.size();
            const int node = nodeAlong(s, j);
            if (atEnd &&
                (graph.nodes[static_cast<std::size_t>(node)].tip || node == graph.rootNode))
                break;
            const int stay = atEnd ? 0 : leavesBeyond(graph, meeting, s, j);
            int best = kNone, bestCount = stay;
            for (std::size_t t = 0; t < strands.strands.size(); ++t) {
                Strand& other = strands.strands[t];
                if (static_cast<int>(t) == current || other.startNode == other.endNode ||
                    std::find(stem.begin(), stem.end(), static_cast<int>(t)) != stem.end())
                    continue;
                if (other.endNode == node) reverseStrand(other);
                if (other.startNode != node) continue;
                if (const int n = leavesBeyond(graph, meeting, other, 0); n > bestCount)
                    best = static_cast<int>(t), bestCount = n;
            }
            if (best == kNone) continue;
            if (!atEnd) {
                splitOff(strands, static_cast<std::size_t>(current), j);
                ++meeting[static_cast<std::size_t>(node)];  // the piece left behind starts here
            }
            current = best;
            stem.push_back(current);
            turned = true;
        }
    }
    // The top: the stem ends at the highest node another strand meets; above it, a leaf.
    const Strand& top = strands.strands[static_cast<std::size_t>(current)];
    const std::size_t edges = top.edges.size();
    const bool endCarries = !graph.nodes[static_cast<std::size_t>(top.endNode)].tip &&
                            meeting[static_cast<std::size_t>(top.endNode)] > 1;
    std::size_t last = endCarries ? edges : 0;
    for (std::size_t j = 1; j < edges && !endCarries; ++j)
        if (meeting[static_cast<std::size_t>(nodeAlong(top, j))] > 1) last = j;
    if (last > 0 && last < edges) splitOff(strands, static_cast<std::size_t>(current), last);
    // A strand through a node of the stem is a pair of leaves leaving it there on both sides
    // (the smoothest continuation joins the two into one arch; maize's leaves are alternate), or
    // at the stem's top, where nothing runs on, the top pair: each is a leaf of its own from the
    // node. A leaf crossing the stem in the image without leaving it is cut there too: the
    // skeleton does not tell the two apart.
    std::vector<int> stemNodes;
    for (const int t : stem) {
        const Strand& st = strands.strands[static_cast<std::size_t>(t)];
        for (std::size_t j = 0; j <= st.edges.size(); ++j) stemNodes.push_back(nodeAlong(st, j));
    }
    for (std::size_t i = 0; i < strands.strands.size(); ++i) {
        if (std::find(stem.begin(), stem.end(), static_cast<int>(i)) != stem.end()) continue;
        const std::vector<int>& through = strands.strands[i].through;
        const auto at = std::find_if(through.begin(), through.end(), [&](int n) {
            return n != graph.rootNode &&
                   std::find(stemNodes.begin(), stemNodes.end(), n) != stemNodes.end();
        });
        if (at != through.end())
            splitOff(strands, i, static_cast<std::size_t>(at - through.begin()) + 1);
    }
    return stem;
}

}  // namespace meadow::capture::segmentation
