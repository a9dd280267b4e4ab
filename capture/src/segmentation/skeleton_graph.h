#pragma once
// A mask's skeleton as a graph, and its edges joined into strands through the junctions.
//
// Nodes are the skeleton's tips, its junctions (touching pixels with three or more skeleton
// neighbours, one node) and the root; edges are the one-pixel paths between them. Where leaves
// cross or touch, the skeleton meets at a junction (or at two close ones, merged into one); there
// each edge is joined to the edge that continues it most smoothly in direction and in depth, as
// leaf-tracing tools in plant phenotyping do. A strand is a chain of edges joined that way: one
// leaf, or the stem, however many others cross it.
#include <opencv2/core.hpp>
#include <vector>

namespace meadow::capture::segmentation {

struct SkeletonNode {
    std::vector<cv::Point> pixels;  // one for a tip or the root; a junction's touching pixels
    cv::Point2f centre;
    bool tip = false;       // an end of the skeleton (one neighbour)
    bool root = false;      // where the plant stands
    std::vector<int> ends;  // edge ends here: 2 x edge + 0 (the edge's front) or + 1 (its back)
};

struct SkeletonEdge {
    std::vector<cv::Point> pixels;  // from node `from` to node `to`, neither node's pixels
    int from = 0, to = 0;
};

struct SkeletonGraph {
    std::vector<SkeletonNode> nodes;
    std::vector<SkeletonEdge> edges;
    int rootNode = -1;
};

// The graph of a one-pixel skeleton (8-connected), with `root`, a skeleton pixel, as a node of
// its own unless it is a tip or part of a junction (then that node is the root).
SkeletonGraph skeletonGraph(const cv::Mat1b& skeleton, cv::Point root);

// Removes, in place, the skeleton's spurs: edges from a junction to a tip (not the root) of
// fewer than `minLength_px` pixels, which a bump in the mask's edge leaves. Repeats until none
// is left, since removing one can make another. Returns how many it removed.
int removeSpurs(cv::Mat1b& skeleton, cv::Point root, float minLength_px);

// Merges junctions joined by an edge shorter than the mask's width there: two leaves crossing
// at an angle thin to two junctions a short bridge apart, not to one. A merged junction holds
// one crossing (it spans no more than the mask's width, or four edges leave it); at the root
// any tangle merges. `halfWidth_px` is the distance transform of the mask (distance to its edge).
void mergeCloseJunctions(SkeletonGraph& graph, const cv::Mat1f& halfWidth_px);

struct StrandParams {
    float maxBend_deg = 45.f;       // an edge continues another only if it turns less than this
    float maxDepthStep_mm = 100.f;  // ...and their depths, carried to the junction, meet this close
};

// One chain of edges through the junctions where each was joined to the next.
struct Strand {
    std::vector<int> edges;            // in order
    std::vector<bool> forward;         // edge i runs from -> to (else to -> from)
    std::vector<int> through;          // nodes passed through, between edge i and edge i + 1
    int startNode = -1, endNode = -1;  // a closed loop starts and ends at the same node
    // The strand's pixels in order, from startNode's nearest pixel to endNode's.
    std::vector<cv::Point> path(const SkeletonGraph& graph) const;
};

struct Strands {
    std::vector<Strand> strands;
    std::vector<int> strandOfEdge;  // per edge
};

// Joins, at every junction but the root, the pairs of edges that continue each other most
// smoothly: the pair that turns least first, while it turns less than maxBend_deg and, where
// `depth_mm` holds readings near the junction on both, their depths carried to it differ by less
// than maxDepthStep_mm. At the root nothing is joined: every edge leaving it starts a strand.
// `halfWidth_px` (the distance to the mask's edge) tells how far from a junction its own bend
// reaches: directions are read beyond it.
Strands followStrands(const SkeletonGraph& graph, const cv::Mat1f& halfWidth_px,
                      const cv::Mat1w& depth_mm, const StrandParams& params);

// The stem: from the root, the strand that carries the most leaves (other strands that end on
// its nodes or run through them: two leaves leaving a node on both sides line up as one strand
// through it); up along it, and at its end, where a strand that ends on it carries more leaves
// beyond that node than its own continuation, the stem turns into that strand and what it leaves
// becomes a leaf of its own; at the top, the stem ends at the highest node another strand ends at,
// and what runs on above becomes the top leaf; a strand through a node of the stem is cut there
// into the two leaves that leave it on both sides. Splits strands to do so (new strands go at the
// end). Returns the stem's strands in order from the root, each turned to run upwards; empty when
// no strand from the root carries a leaf (a lone leaf, or blades fanning from the root itself).
std::vector<int> followStem(const SkeletonGraph& graph, Strands& strands);

}  // namespace meadow::capture::segmentation
