#pragma once
// A plant that turned between views (a turntable) shows each leaf in several of them, each time
// cut differently: whole where it stands clear, short where another leaf or the stem hides its
// base. Once the views are registered (capture/view_registration.h), the archetypes of one leaf
// lie along one another in the chain's space. A leaf's length is taken from the longest of them
// that another view confirms (shows nearly as long along it): one that runs on past the leaf,
// into another leaf or down the stem, is seen so once. The shorter ones are left out of the
// library for it, their views listed in its source (Source::alsoSeenIn) (see
// docs/capture.md#turntable-views). An archetype no other view shows is told apart, to be left
// out as a piece or a false blade.
#include <vector>

#include "meadow/capture/view_registration.h"
#include "meadow/modeling/archetype.h"

namespace meadow::modeling {

struct ViewJoinParams {
    // Two archetypes are one leaf when the upper three quarters of the shorter one's spine lie,
    // on average, within the larger of these of the longer one's: registration and segmentation
    // each move a leaf's spine by a few millimetres between views.
    float maxDistance_m = 0.01f;
    float maxDistanceFraction = 0.05f;  // of the shorter one's length
    // An archetype is a leaf's whole length only where another view's, at least this share of
    // its length, lies along it; only such archetypes are kept for others.
    float confirmingLength = 0.8f;
};

struct ViewJoinResult {
    int leftOut = 0;  // archetypes left out for a longer one of their leaf
    // Indices, into the archetypes kept, of those seen in one view only: no archetype of another
    // view of their chain lies along them, though the chain has two views or more. A leaf stands
    // in several views of a turning plant; a piece of one, cut where it crosses another, and a
    // false blade are cut differently in each and rarely lie along anything.
    std::vector<std::size_t> seenOnce;
};

// Among the archetypes placed in registered views: those another view's archetype, at least
// confirmingLength of their length, lies along (or they along it) are confirmed; longest first,
// confirmed ones before the rest, each archetype is left out for the nearest longer confirmed one
// kept that it lies along, of the same chain and another view (ViewJoinParams), or kept. The kept
// one's Source::alsoSeenIn lists the left-out ones' sightings. Archetypes from frames not in
// `views` are left as they are. The order of those kept is unchanged.
ViewJoinResult joinSameLeafAcrossViews(std::vector<Archetype>& archetypes,
                                       const std::vector<capture::RegisteredView>& views,
                                       const ViewJoinParams& params = {});

}  // namespace meadow::modeling
