// Observations of one blade across fused groups linked into tracks, and their mean skeleton
// (blade_tracks.h).
#include "meadow/modeling/blade_tracks.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <stdexcept>

#include "chain_resample.h"
#include "meadow/modeling/hausdorff.h"
#include "upper_distance.h"

namespace meadow::modeling {
namespace {

using detail::polylineLength_m;
using detail::upperDistance_m;

// Element-wise mean of one member vector of every skeleton; the first skeleton's when their sizes
// differ (a field the skeleton leaves empty).
template <typename T, typename Member>
std::vector<T> meanOf(const std::vector<const Skeleton*>& skeletons, Member member) {
    const std::vector<T>& first = skeletons.front()->*member;
    for (const Skeleton* s : skeletons)
        if ((s->*member).size() != first.size()) return first;
    std::vector<T> mean(first.size(), T(0));
    const float share = 1.f / static_cast<float>(skeletons.size());
    for (const Skeleton* s : skeletons)
        for (std::size_t j = 0; j < first.size(); ++j) mean[j] += (s->*member)[j] * share;
    return mean;
}

// The skeletons of the track's members that its mean takes (membersForMean).
std::vector<const Skeleton*> skeletonsForMean(const std::vector<BladeObservation>& observations,
                                              const std::vector<std::size_t>& track,
                                              const BladeTrackParams& params) {
    std::vector<const Skeleton*> skeletons;
    for (const std::size_t i : membersForMean(observations, track, params))
        skeletons.push_back(&observations[i].skeleton);
    return skeletons;
}

}  // namespace

float skeletonDistance_m(const Skeleton& a, const Skeleton& b) {
    return upperDistance_m(a.points_m, polylineLength_m(a.points_m), b.points_m,
                           polylineLength_m(b.points_m));
}

Skeleton trackSkeleton(const std::vector<BladeObservation>& observations,
                       const std::vector<std::size_t>& track, const BladeTrackParams& params) {
    return meanSkeleton(skeletonsForMean(observations, track, params));
}

std::vector<std::size_t> membersForMean(const std::vector<BladeObservation>& observations,
                                        const std::vector<std::size_t>& track,
                                        const BladeTrackParams& params) {
    if (track.size() <= 1) return track;
    int rooted = 0;
    for (const std::size_t i : track) rooted += !observations[i].skeleton.baseNotRooted;
    const bool majorityRooted = 2 * rooted >= static_cast<int>(track.size());
    std::vector<std::size_t> same;
    std::vector<float> lengths;
    for (const std::size_t i : track)
        if (!observations[i].skeleton.baseNotRooted == majorityRooted) {
            same.push_back(i);
            lengths.push_back(polylineLength_m(observations[i].skeleton.points_m));
        }
    std::vector<float> sorted = lengths;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2),
                     sorted.end());
    const float medianLength = sorted[sorted.size() / 2];
    std::vector<std::size_t> kept;
    for (std::size_t k = 0; k < same.size(); ++k)
        if (std::abs(lengths[k] - medianLength) <= params.maxLengthDeviation * medianLength)
            kept.push_back(same[k]);
    return kept;  // never empty: the median's own member is within any deviation
}

std::vector<std::vector<std::size_t>> trackBlades(const std::vector<BladeObservation>& observations,
                                                  const BladeTrackParams& params) {
    std::map<int, std::vector<std::size_t>> byGroup;
    for (std::size_t i = 0; i < observations.size(); ++i)
        byGroup[observations[i].group].push_back(i);
    std::vector<std::vector<std::size_t>> tracks;
    std::vector<int> lastGroup;
    // Each track's mean points and their length, recomputed when the track takes a view.
    std::vector<std::vector<glm::vec3>> means;
    std::vector<float> meanLengths;
    const auto refresh = [&](std::size_t t) {
        // Only the points: linking needs no more of the mean skeleton.
        means[t] = meanOf<glm::vec3>(skeletonsForMean(observations, tracks[t], params),
                                     &Skeleton::points_m);
        meanLengths[t] = polylineLength_m(means[t]);
    };
    for (const auto& [group, members] : byGroup) {
        struct Pair {
            float ratio;
            std::size_t observation, track;
        };
        std::vector<Pair> pairs;
        if (params.enabled) {
            std::vector<float> lengths;  // of this group's views, once for all tracks
            for (const std::size_t o : members)
                lengths.push_back(polylineLength_m(observations[o].skeleton.points_m));
            for (std::size_t t = 0; t < tracks.size(); ++t)
                for (std::size_t m = 0; m < members.size(); ++m) {
                    const std::size_t o = members[m];
                    const float length = std::min(meanLengths[t], lengths[m]);
                    const float ratio =
                        upperDistance_m(observations[o].skeleton.points_m, lengths[m], means[t],
                                        meanLengths[t], params.maxDistanceFraction * length) /
                        length;
                    if (ratio <= params.maxDistanceFraction) pairs.push_back({ratio, o, t});
                }
        }
        std::stable_sort(pairs.begin(), pairs.end(),
                         [](const Pair& a, const Pair& b) { return a.ratio < b.ratio; });
        std::vector<char> joined(observations.size(), 0);
        for (const Pair& p : pairs) {
            if (joined[p.observation] || lastGroup[p.track] == group) continue;
            tracks[p.track].push_back(p.observation);
            lastGroup[p.track] = group;
            joined[p.observation] = 1;
            refresh(p.track);
        }
        // Tracks open group by group, in observation order within a group: a capture of one
        // group lists its blades as the segmenter found them.
        for (const std::size_t o : members)
            if (!joined[o]) {
                tracks.push_back({o});
                lastGroup.push_back(group);
                means.emplace_back();
                meanLengths.push_back(0.f);
                refresh(tracks.size() - 1);
            }
    }
    return tracks;
}

Skeleton meanSkeleton(const std::vector<const Skeleton*>& skeletons) {
    if (skeletons.empty()) throw std::invalid_argument("meanSkeleton: no skeletons");
    const std::size_t n = skeletons.front()->points_m.size();
    for (const Skeleton* s : skeletons)
        if (s->points_m.size() != n || s->width_m.size() != n)
            throw std::invalid_argument("meanSkeleton: skeletons of different point counts");
    if (skeletons.size() == 1) return *skeletons.front();
    Skeleton mean = *skeletons.front();
    mean.points_m = meanOf<glm::vec3>(skeletons, &Skeleton::points_m);
    mean.width_m = meanOf<float>(skeletons, &Skeleton::width_m);
    mean.depth_m = meanOf<float>(skeletons, &Skeleton::depth_m);
    mean.arcFraction = meanOf<float>(skeletons, &Skeleton::arcFraction);
    mean.midline_px = meanOf<glm::vec2>(skeletons, &Skeleton::midline_px);
    mean.width_px = meanOf<float>(skeletons, &Skeleton::width_px);
    mean.across_px = meanOf<glm::vec2>(skeletons, &Skeleton::across_px);
    for (glm::vec2& a : mean.across_px)
        if (const float l = glm::length(a); l > 0.f) a /= l;
    // The across steps of the sightings that read one (a zero step was not read).
    if (std::all_of(skeletons.begin(), skeletons.end(),
                    [n](const Skeleton* s) { return s->acrossStep_m.size() == n; })) {
        for (std::size_t j = 0; j < n; ++j) {
            glm::vec3 sum(0.f);
            int read = 0;
            for (const Skeleton* s : skeletons)
                if (s->acrossStep_m[j] != glm::vec3(0.f)) sum += s->acrossStep_m[j], ++read;
            mean.acrossStep_m[j] = read > 0 ? sum / static_cast<float>(read) : glm::vec3(0.f);
        }
    } else {
        mean.acrossStep_m.clear();
    }
    const float count = static_cast<float>(skeletons.size());
    float base = 0.f, tip = 0.f, rootPoints = 0.f, tipPoints = 0.f, sides = 0.f, ridge = 0.f;
    int notRooted = 0, asymmetric = 0, filled = 0;
    mean.reasons.clear();
    for (const Skeleton* s : skeletons) {
        base += s->baseExtension_m, tip += s->tipExtension_m;
        rootPoints += static_cast<float>(s->rootPoints);
        tipPoints += static_cast<float>(s->tipPoints);
        sides += s->sideLengthRatio, ridge += s->ridgeOffsetFraction;
        notRooted += s->baseNotRooted, asymmetric += s->asymmetric, filled += s->filledDepths;
        for (const std::string& r : s->reasons)
            if (std::find(mean.reasons.begin(), mean.reasons.end(), r) == mean.reasons.end())
                mean.reasons.push_back(r);
    }
    mean.baseExtension_m = base / count;
    mean.tipExtension_m = tip / count;
    mean.rootPoints = static_cast<int>(std::lround(rootPoints / count));
    mean.tipPoints = static_cast<int>(std::lround(tipPoints / count));
    mean.sideLengthRatio = sides / count;
    mean.ridgeOffsetFraction = ridge / count;
    mean.baseNotRooted = 2 * notRooted > static_cast<int>(skeletons.size());
    mean.asymmetric = 2 * asymmetric > static_cast<int>(skeletons.size());
    mean.filledDepths = static_cast<int>(std::lround(static_cast<float>(filled) / count));
    return mean;
}

}  // namespace meadow::modeling
