#pragma once
// The middle of the capture job (capture_pipeline.h): each group's segmentation gives a skeleton
// per blade it vouches for; the skeletons of one blade across groups form a track; each track
// is fitted once, to the mean of its skeletons (blade_tracks.h).
#include <opencv2/core/mat.hpp>
#include <set>
#include <string>
#include <vector>

#include "meadow/capture/group_segmenter.h"
#include "meadow/capture/intrinsics.h"
#include "meadow/modeling/archetype.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/blade_tracks.h"
#include "meadow/modeling/capture_pipeline.h"

namespace meadow::modeling {

// What fitting a tracked blade needs of each view besides its skeleton.
struct BladeView {
    BladeSighting sighting;          // frame and blade id
    std::vector<std::string> flags;  // the segmenter's reason lines
    cv::Mat1b mask;                  // for the distance-transform width check
    cv::Point maskOrigin_px;
    capture::Intrinsics intrinsics;
};

struct BladeObservations {
    std::vector<BladeObservation> skeletons;  // per view, as trackBlades takes them
    std::vector<BladeView> views;             // parallel to skeletons
    std::set<int> movingGroups;               // groups of runs in which the tuft moved
};

// Adds the skeleton of every blade of `group` that may be modelled (CaptureOptions::keepFlagged,
// disqualifiesFromModelling) to `observations`; counts and notes in `summary` what it found,
// skipped and could not skeletonise, and writes the debug overlay when asked.
void observeGroup(const capture::GroupSegmentation& group, const CaptureOptions& options,
                  BladeObservations& observations, CaptureSummary& summary);

// One track of view indices per blade (trackBlades), except that a track holding a view from a
// moving run is one track per view: the mean of a moving blade's views is no view of it.
std::vector<std::vector<std::size_t>> trackObservations(const BladeObservations& observations,
                                                        const BladeTrackParams& params);

struct TrackFit {
    BladeFit fit;                    // fit.archetype is what the library keeps
    std::vector<std::size_t> track;  // the views it was fitted to
};
// What CaptureSummary::skippedBy and a kept archetype's source flags call a fit too short for its
// width (CaptureOptions::minLengthToWidth).
inline constexpr const char* kTooShortForItsWidth = "too-short-for-its-width";
// What they call an archetype of a turning plant that no other view shows (ViewJoinResult).
inline constexpr const char* kSeenOnce = "seen-in-one-view-only";

// One archetype per track, fitted to the mean of its skeletons, named by its first view;
// failures, and fits too short for their width, are noted in `summary`, not thrown.
std::vector<TrackFit> fitTracks(const BladeObservations& observations,
                                const std::vector<std::vector<std::size_t>>& tracks,
                                const CaptureOptions& options, const std::string& sourceName,
                                CaptureSummary& summary);

}  // namespace meadow::modeling
