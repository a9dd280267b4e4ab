#pragma once
// The capture job end to end: a depth source -> fused groups and their segmentations
// (capture/group_segmenter.h) -> a skeleton per trustworthy blade of each group
// (blade_observations.h) -> one track per blade over the groups (blade_tracks.h) -> one
// archetype fitted per track -> an archetype library.
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "meadow/capture/blade_contour.h"
#include "meadow/capture/depth_source.h"
#include "meadow/capture/group_segmenter.h"
#include "meadow/capture/segmenter.h"
#include "meadow/modeling/archetype_library.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/blade_tracks.h"
#include "meadow/modeling/view_joining.h"

namespace meadow::modeling {

struct CaptureOptions {
    capture::SegmenterParams segmenter;
    capture::GroupingParams groups;  // fusion, recurring readings, motion test
    BladeFitParams fit;
    int maxFrames = 0;         // stop after this many frames; 0 = the whole source
    int maxArchetypes = 0;     // merge near-duplicates down to this many; 0 = keep every blade
    bool keepFlagged = false;  // also model blades the segmenter flagged (overlap, curl, ...)
    // An archetype shorter along its spine than this many times its widest width is a piece of a
    // leaf (cut where it crosses another or meets the stem), not a blade: it is not kept, unless
    // keepFlagged (then its source lists why). Grass leaves are many times longer than wide.
    // 0 = keep every shape.
    float minLengthToWidth = 2.f;
    BladeTrackParams tracks;  // one archetype per blade across groups (enabled = false: per group)
    // With groups.turning (a turntable), the views are registered to one another and a leaf's
    // archetypes that another view shows longer left out (view_joining.h), unless
    // tracks.enabled is false.
    capture::ViewRegistrationParams registration;
    ViewJoinParams joining;
    std::filesystem::path debugDir;  // overlay PNG per segmentation when not empty
};

struct CaptureSummary {
    int framesRead = 0;
    int segmentations = 0;
    int bladesFound = 0;
    int bladesModelled = 0;        // observations behind the library's archetypes
    int averagedArchetypes = 0;    // archetypes fitted to two or more observations
    int emptySegmentations = 0;    // segmentations that found no blade
    int noPlantSegmentations = 0;  // of them, those that saw no plant at all
    std::string noPlant;           // the first one's reason ("no plant in view: ...")
    int motionTests = 0;           // runs tested for motion (GroupingParams::checkMotion)
    int movingRuns = 0;            // of them, runs in which the tuft moved
    std::string motion;            // the first moving run's measurement, for the CLI
    // Of the moving runs, those whose plant turned (capture::TuftMotion::turned): their frames
    // are registered as a turning plant's views, as --turntable's are.
    int turningRuns = 0;
    // A turning plant's views (GroupingParams::turning, or turning runs): how many were registered
    // to a view before them, in how many chains, and how many archetypes were left out for a longer
    // one of their leaf; with a note per view (its turn, or why it starts a chain).
    int turningViews = 0;
    int registeredViews = 0;
    int viewChains = 0;
    int joinedArchetypes = 0;
    std::map<std::string, int> skippedBy;    // flag name -> blades it kept from modelling
    std::vector<std::string> notes;          // one line per skipped blade or empty segmentation
    std::map<std::string, double> stage_ms;  // wall time of each segmentation stage, summed
};

// What the blades were skipped as, with counts, and what to do about blades too thin to model
// ("" when none was skipped): "skipped as too-thin (5), overlapping (3); blades under ~3 px
// wide: bring the camera closer ... or pass --keep-flagged to model them anyway".
std::string skippedSummary(const CaptureSummary& summary);

struct CaptureResult {
    ArchetypeLibrary library;
    CaptureSummary summary;
    // A turning plant's views as registered (view_registration.h); empty without one.
    std::vector<capture::RegisteredView> turningViews;
    capture::LoopClosure turningLoop;  // its last view on its first (ViewRegistrar::closeLoop)
};

// Whether a segmenter flag keeps captureArchetypes from modelling the blade (unless
// CaptureOptions::keepFlagged): after it the contour does not describe one whole blade.
// Asymmetry does not: the fit measures and records it.
bool disqualifiesFromModelling(capture::BladeFlag flag);

using CaptureProgress = std::function<void(int framesDone, int framesTotal)>;

// Throws ModelingError when no blade could be modelled (the message carries the reasons), the
// source's CaptureError for unreadable input, and CaptureError for unusable options.
CaptureResult captureArchetypes(capture::DepthSource& source, const std::string& sourceName,
                                const CaptureOptions& options,
                                const CaptureProgress& progress = {});

}  // namespace meadow::modeling
