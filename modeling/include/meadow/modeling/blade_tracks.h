#pragma once
// One blade of a still tuft, seen once in each fused group of a recording, becomes one archetype:
// its observations are linked into a track by where their skeletons lie in camera space, and the
// track is fitted once, to the mean of its skeletons. The sensor's noise is drawn afresh in every
// frame, so the mean of a blade's skeletons is nearer the blade than any one of them
// (see docs/capture.md#one-archetype-per-blade, docs/measurements/modeling_groups.md).
#include <cstddef>
#include <vector>

#include "meadow/modeling/skeleton.h"

namespace meadow::modeling {

struct BladeTrackParams {
    // false: every observation is its own track (`meadow capture --per-group`), for a tuft that
    // moves between groups or a camera that does.
    bool enabled = true;
    // Two observations are one blade when skeletonDistance_m is within this fraction of the
    // shorter one's length. On the blade-type presets at nominal noise, views of one blade lie
    // well within it and views of two different blades beyond it.
    float maxDistanceFraction = 0.03f;
    // The mean takes a track's members of the majority's rooting (blade_root.h; ties: rooted)
    // whose length lies within this fraction of their median length: a view of the blade cut
    // short, or one not rooted, is still that blade, but averaged point by point it would pull
    // the others' tip down or their root up.
    float maxLengthDeviation = 0.1f;
};

struct BladeObservation {
    int group = 0;      // the fused group that saw it; a track takes at most one per group
    Skeleton skeleton;  // as capture builds it (segmentedBladeSkeleton): rooted, tip continued
};

// Mean distance (m) from the upper three quarters of the shorter skeleton's points to the longer
// skeleton's polyline: the blades of a tuft share their root, so the lower part tells them apart
// least, and a view of a blade cut short lies along the whole one. +inf for a skeleton of fewer
// than 2 points.
float skeletonDistance_m(const Skeleton& a, const Skeleton& b);

// Tracks over the observations, group by group in increasing group order: an observation joins
// the track whose mean skeleton (over membersForMean) lies nearest, within
// params.maxDistanceFraction of the shorter one's length (pairs nearest first, one observation per
// track and group), or starts a new one. Each track lists indices into `observations`, in group
// order; tracks are in order of their first observation.
std::vector<std::vector<std::size_t>> trackBlades(const std::vector<BladeObservation>& observations,
                                                  const BladeTrackParams& params = {});

// The members of `track` that its mean takes (BladeTrackParams::maxLengthDeviation), in track
// order; never empty for a non-empty track.
std::vector<std::size_t> membersForMean(const std::vector<BladeObservation>& observations,
                                        const std::vector<std::size_t>& track,
                                        const BladeTrackParams& params = {});

// The skeleton a track's archetype is fitted to: meanSkeleton of its membersForMean. Requires a
// non-empty track.
Skeleton trackSkeleton(const std::vector<BladeObservation>& observations,
                       const std::vector<std::size_t>& track, const BladeTrackParams& params = {});

// The point-by-point mean of skeletons with equal point counts (positions, widths, depths, the
// pixel midline and across directions), with the added root and tip pieces' lengths and point
// counts averaged, baseNotRooted and asymmetric by majority and the reasons of all, each once.
// One skeleton comes back unchanged. Requires a non-empty list of equal point counts.
Skeleton meanSkeleton(const std::vector<const Skeleton*>& skeletons);

}  // namespace meadow::modeling
