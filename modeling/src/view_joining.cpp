// A turning plant's archetypes of one leaf, joined across its registered views (view_joining.h).
#include "meadow/modeling/view_joining.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>

#include "chain_resample.h"
#include "upper_distance.h"

namespace meadow::modeling {

namespace {

constexpr int kSpineSamples = 17;

// An archetype's spine in its chain's space (RegisteredView::chainFromView), base to tip; empty
// when it is not placed.
std::vector<glm::vec3> spineInChain(const Archetype& archetype,
                                    const capture::RegisteredView& view) {
    if (!archetype.source.placed) return {};
    const glm::mat4 chainFromBlade = view.chainFromView * archetype.source.cameraFromBlade;
    std::vector<glm::vec3> spine;
    spine.reserve(kSpineSamples);
    for (int i = 0; i < kSpineSamples; ++i) {
        const float t = static_cast<float>(i) / static_cast<float>(kSpineSamples - 1);
        spine.emplace_back(chainFromBlade * glm::vec4(archetype.spine_m.at(t), 1.f));
    }
    return spine;
}

}  // namespace

ViewJoinResult joinSameLeafAcrossViews(std::vector<Archetype>& archetypes,
                                       const std::vector<capture::RegisteredView>& views,
                                       const ViewJoinParams& params) {
    std::map<int, const capture::RegisteredView*> viewOfFrame;
    std::map<int, int> viewsInChain;
    for (const capture::RegisteredView& v : views)
        viewOfFrame[v.frame] = &v, ++viewsInChain[v.chain];

    struct Placed {
        std::size_t index;
        int chain;
        std::vector<glm::vec3> spine;
        float length_m;
    };
    std::vector<Placed> placed;
    for (std::size_t i = 0; i < archetypes.size(); ++i) {
        const auto it = viewOfFrame.find(archetypes[i].source.frame);
        if (it == viewOfFrame.end()) continue;
        std::vector<glm::vec3> spine = spineInChain(archetypes[i], *it->second);
        if (spine.empty()) continue;
        const float length = detail::polylineLength_m(spine);
        placed.push_back({i, it->second->chain, std::move(spine), length});
    }
    // Whether the shorter of two lies along the longer (ViewJoinParams), and how far apart.
    const std::size_t n = placed.size();
    std::vector<float> apart(n * n, std::numeric_limits<float>::infinity());
    const auto along = [&](std::size_t i, std::size_t j) { return apart[i * n + j]; };
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j) {
            const Placed& p = placed[i];
            const Placed& q = placed[j];
            if (p.chain != q.chain ||
                archetypes[p.index].source.frame == archetypes[q.index].source.frame)
                continue;
            const float limit =
                std::max(params.maxDistance_m,
                         params.maxDistanceFraction * std::min(p.length_m, q.length_m));
            const float d =
                detail::upperDistance_m(p.spine, p.length_m, q.spine, q.length_m, limit);
            if (d <= limit) apart[i * n + j] = apart[j * n + i] = d;
        }
    // A leaf's length is taken from an archetype another view nearly matches in length along
    // it: one that runs on past the leaf (into another leaf, down the stem) is seen so once.
    std::vector<bool> confirmed(n, false);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n && !confirmed[i]; ++j)
            confirmed[i] =
                std::isfinite(along(i, j)) &&
                std::min(placed[i].length_m, placed[j].length_m) >=
                    params.confirmingLength * std::max(placed[i].length_m, placed[j].length_m);

    // Longest first, the confirmed ones, then the rest: each folds into the nearest longer
    // confirmed one it lies along, or is kept.
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        if (confirmed[a] != confirmed[b]) return static_cast<bool>(confirmed[a]);
        return placed[a].length_m > placed[b].length_m;
    });
    std::vector<bool> folded(archetypes.size(), false), alone(archetypes.size(), false);
    for (std::size_t i = 0; i < n; ++i)
        alone[placed[i].index] =
            viewsInChain.at(placed[i].chain) > 1 &&
            std::none_of(apart.begin() + static_cast<std::ptrdiff_t>(i * n),
                         apart.begin() + static_cast<std::ptrdiff_t>((i + 1) * n),
                         [](float d) { return std::isfinite(d); });
    std::vector<std::size_t> keepers;  // into `placed`
    ViewJoinResult result;
    for (std::size_t i : order) {
        std::optional<std::size_t> into;
        float nearest = std::numeric_limits<float>::infinity();
        for (std::size_t k : keepers)
            if (placed[k].length_m >= placed[i].length_m && along(i, k) < nearest)
                nearest = along(i, k), into = k;
        if (!into) {
            if (confirmed[i]) keepers.push_back(i);
            continue;
        }
        Source& keeper = archetypes[placed[*into].index].source;
        const Source& source = archetypes[placed[i].index].source;
        keeper.alsoSeenIn.push_back({source.frame, source.bladeId});
        folded[placed[i].index] = true;
        ++result.leftOut;
    }
    std::size_t next = 0;
    for (std::size_t i = 0; i < archetypes.size(); ++i)
        if (!folded[i]) {
            if (alone[i]) result.seenOnce.push_back(next);
            if (next != i) archetypes[next] = std::move(archetypes[i]);
            ++next;
        }
    archetypes.resize(next);
    return result;
}

}  // namespace meadow::modeling
