// Skeleton refining: movement similarity (Fan & Sheng 2017, Eq. 1-3, Algorithm 1) and the
// baselines of their Fig. 12.
#include "meadow/modeling/skeleton_refiner.h"

#include <algorithm>
#include <glm/geometric.hpp>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "meadow/core/random.h"

namespace meadow::modeling {
namespace {

void checkCounts(int knotCount, int m, const char* who) {
    if (m < 2 || knotCount < 2)
        throw std::invalid_argument(std::string(who) +
                                    ": need m >= 2 and >= 2 knots, got m = " + std::to_string(m) +
                                    ", " + std::to_string(knotCount) + " knots");
}

std::vector<int> allIndices(int n) {
    std::vector<int> v(static_cast<std::size_t>(n));
    std::iota(v.begin(), v.end(), 0);
    return v;
}

// Algorithm 1's greedy loop, shared by movement similarity and geometry-only (which differ only
// in the pair cost): the knots in the order it drops them until `m` remain. Kept knots form a
// linked list; each step merges the cheapest adjacent pair. The steps do not depend on m, so
// stopping later only adds to the order.
template <class Cost>
std::vector<int> dropOrder(int n, int m, const Cost& cost) {
    std::vector<int> dropped;
    if (m >= n) return dropped;
    std::vector<int> prev(static_cast<std::size_t>(n)), next(static_cast<std::size_t>(n));
    std::vector<float> pairCost(static_cast<std::size_t>(n), 0.f);  // cost of (i, next[i])
    for (int i = 0; i < n; ++i) {
        prev[i] = i - 1;
        next[i] = i + 1 < n ? i + 1 : -1;
        if (next[i] >= 0) pairCost[i] = cost(i, next[i]);
    }
    for (int remaining = n; remaining > m; --remaining) {
        int a = -1;
        float best = std::numeric_limits<float>::max();
        for (int i = 0; i != -1 && next[i] != -1; i = next[i])
            if (pairCost[i] < best) best = pairCost[i], a = i;
        const int b = next[a];
        // Merge (a, b): the endpoints always stay; otherwise drop the knot whose removal leaves
        // the cheaper new pair.
        int drop;
        if (prev[a] == -1)
            drop = b;
        else if (next[b] == -1)
            drop = a;
        else
            drop = cost(prev[a], b) <= cost(a, next[b]) ? a : b;
        const int p = prev[drop], q = next[drop];
        next[p] = q;
        prev[q] = p;
        pairCost[p] = cost(p, q);
        dropped.push_back(drop);
    }
    return dropped;
}

// The knots of 0..n-1 left after the first n - m of `dropped`, ascending.
std::vector<int> keptAfter(int n, const std::vector<int>& dropped, int m) {
    std::vector<char> gone(static_cast<std::size_t>(n), 0);
    const auto count =
        static_cast<std::size_t>(std::clamp(n - m, 0, static_cast<int>(dropped.size())));
    for (std::size_t i = 0; i < count; ++i) gone[static_cast<std::size_t>(dropped[i])] = 1;
    std::vector<int> kept;
    for (int i = 0; i < n; ++i)
        if (!gone[static_cast<std::size_t>(i)]) kept.push_back(i);
    return kept;
}

template <class Cost>
std::vector<int> greedyMerge(int n, int m, const Cost& cost) {
    return keptAfter(n, dropOrder(n, m, cost), m);
}

void checkFrames(const KnotTrajectories& frames) {
    if (frames.empty()) throw std::invalid_argument("refineByMovementSimilarity: no frames");
    for (const auto& f : frames)
        if (f.size() != frames.front().size())
            throw std::invalid_argument("refineByMovementSimilarity: frames differ in knot count");
}

}  // namespace

float meanDistance_m(const KnotTrajectories& frames, int a, int b) {
    double sum = 0.0;
    for (const auto& f : frames) sum += glm::distance(f[a], f[b]);
    return static_cast<float>(sum / static_cast<double>(frames.size()));
}

float movementVariance_m2(const KnotTrajectories& frames, int a, int b) {
    glm::dvec3 mean{0.0};
    for (const auto& f : frames) mean += glm::dvec3(f[b] - f[a]);
    mean /= static_cast<double>(frames.size());
    double sum = 0.0;
    for (const auto& f : frames) {
        const glm::dvec3 d = glm::dvec3(f[b] - f[a]) - mean;
        sum += glm::dot(d, d);
    }
    return static_cast<float>(sum / static_cast<double>(frames.size()));
}

float movementDifference(float dis, float var, float mu, float disScale, float varScale) {
    return mu * dis / disScale + (1.f - mu) * var / varScale;
}

namespace {
// Algorithm 1 with the movement difference as the pair cost, dropping knots until m remain.
std::vector<int> movementSimilarityDrops(const KnotTrajectories& frames, int m,
                                         const RefinerParams& params) {
    const int n = static_cast<int>(frames.front().size());
    if (!(params.mu >= 0.f && params.mu <= 1.f))
        throw std::invalid_argument("refineByMovementSimilarity: mu must be in [0, 1], got " +
                                    std::to_string(params.mu));
    // Scales of the two terms on the full chain (see movementDifference).
    double disSum = 0.0, varSum = 0.0;
    for (int i = 0; i + 1 < n; ++i)
        disSum += meanDistance_m(frames, i, i + 1), varSum += movementVariance_m2(frames, i, i + 1);
    const float disScale = disSum > 0.0 ? static_cast<float>(disSum / (n - 1)) : 1.f;
    const float varScale = varSum > 0.0 ? static_cast<float>(varSum / (n - 1)) : 1.f;
    return dropOrder(n, m, [&](int a, int b) {
        return movementDifference(meanDistance_m(frames, a, b), movementVariance_m2(frames, a, b),
                                  params.mu, disScale, varScale);
    });
}
}  // namespace

std::vector<int> refineByMovementSimilarity(const KnotTrajectories& frames, int m,
                                            const RefinerParams& params) {
    checkFrames(frames);
    const int n = static_cast<int>(frames.front().size());
    checkCounts(n, m, "refineByMovementSimilarity");
    return keptAfter(n, movementSimilarityDrops(frames, m, params), m);
}

std::vector<int> movementSimilarityDropOrder(const KnotTrajectories& frames,
                                             const RefinerParams& params) {
    checkFrames(frames);
    const int n = static_cast<int>(frames.front().size());
    checkCounts(n, 2, "movementSimilarityDropOrder");
    return movementSimilarityDrops(frames, 2, params);
}

std::vector<int> keptAfterDrops(int knotCount, const std::vector<int>& dropOrder, int m) {
    checkCounts(knotCount, m, "keptAfterDrops");
    return keptAfter(knotCount, dropOrder, m);
}

std::vector<int> refineGeometryOnly(const std::vector<glm::vec3>& knots, int m) {
    const int n = static_cast<int>(knots.size());
    checkCounts(n, m, "refineGeometryOnly");
    return greedyMerge(n, m, [&](int a, int b) { return glm::distance(knots[a], knots[b]); });
}

std::vector<int> refineMean(const std::vector<glm::vec3>& knots, int m) {
    const int n = static_cast<int>(knots.size());
    checkCounts(n, m, "refineMean");
    if (m >= n) return allIndices(n);
    std::vector<float> arc(static_cast<std::size_t>(n), 0.f);
    for (int i = 1; i < n; ++i) arc[i] = arc[i - 1] + glm::distance(knots[i - 1], knots[i]);
    std::vector<int> kept{0};
    for (int k = 1; k + 1 < m; ++k) {
        const float target = arc.back() * static_cast<float>(k) / static_cast<float>(m - 1);
        int best = static_cast<int>(std::lower_bound(arc.begin(), arc.end(), target) - arc.begin());
        if (best > 0 && target - arc[best - 1] < arc[best] - target) --best;
        // Keep indices strictly increasing and leave room for the knots still to come.
        best = std::clamp(best, kept.back() + 1, n - 1 - (m - 1 - k));
        kept.push_back(best);
    }
    kept.push_back(n - 1);
    return kept;
}

std::vector<int> refineRandom(int knotCount, int m, std::uint64_t seed) {
    checkCounts(knotCount, m, "refineRandom");
    if (m >= knotCount) return allIndices(knotCount);
    std::vector<int> interior(static_cast<std::size_t>(knotCount - 2));
    std::iota(interior.begin(), interior.end(), 1);
    Rng rng(seed);
    std::shuffle(interior.begin(), interior.end(), rng.engine());
    std::vector<int> kept(interior.begin(), interior.begin() + (m - 2));
    kept.push_back(0);
    kept.push_back(knotCount - 1);
    std::sort(kept.begin(), kept.end());
    return kept;
}

std::vector<int> refine(RefinerKind kind, const std::vector<glm::vec3>& restKnots,
                        const KnotTrajectories& frames, int m, const RefinerParams& params) {
    switch (kind) {
        case RefinerKind::MovementSimilarity:
            return refineByMovementSimilarity(frames, m, params);
        case RefinerKind::Random:
            return refineRandom(static_cast<int>(restKnots.size()), m, params.seed);
        case RefinerKind::Mean:
            return refineMean(restKnots, m);
        case RefinerKind::GeometryOnly:
            return refineGeometryOnly(restKnots, m);
    }
    throw std::invalid_argument("refine: unknown refiner kind");
}

}  // namespace meadow::modeling
