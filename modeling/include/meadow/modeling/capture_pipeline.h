#pragma once
// The capture job end to end: a depth source -> segmentation -> one archetype per trustworthy
// blade -> an archetype library. Frames are taken in groups of `fusionFrames` (fused by the
// segmenter's per-pixel median, for a still tuft); every group yields its own observations of
// the blades, and a blade seen in several groups is fitted once, to the mean of its skeletons
// (blade_tracks.h).
#include <filesystem>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "meadow/capture/depth_source.h"
#include "meadow/capture/segmenter.h"
#include "meadow/capture/tuft_motion.h"
#include "meadow/modeling/archetype_library.h"
#include "meadow/modeling/blade_fit.h"
#include "meadow/modeling/blade_tracks.h"

namespace meadow::modeling {

struct CaptureOptions {
    capture::SegmenterParams segmenter;
    BladeFitParams fit;
    int fusionFrames = 3;      // frames fused per segmentation; 1 = every frame on its own
    int maxFrames = 0;         // stop after this many frames; 0 = the whole source
    int maxArchetypes = 0;     // merge near-duplicates down to this many; 0 = keep every blade
    bool keepFlagged = false;  // also model blades the segmenter flagged (overlap, curl, ...)
    BladeTrackParams tracks;   // one archetype per blade across groups (enabled = false: per group)
    // Tip trails also follow readings that recur over this many frames of a still tuft
    // (capture/recurring_readings.h), taken over the last recurringFrames frames (rounded up to
    // whole groups) when a run of groups is segmented; fewer frames in all, or 0: each group's
    // trails see its own readings only. Measured (README, "Tips from readings that recur over
    // frames"): sharp-tip's tip RMS from 12 frames 8.30 -> 4.20 mm, shrub-leaf's 4.40 -> 2.84 mm.
    int recurringFrames = 12;
    capture::RecurringParams recurring;
    // Before a run's recurring readings are used, the run is tested for motion
    // (capture/tuft_motion.h): a tuft that moved over it breaks what they and the mean of a
    // blade's views assume, so such a run is segmented without them and its blades are modelled
    // one archetype per group. Measured on the wind preset (seeds 1-3, 0.6-1.0 m): tip RMS 80.0
    // -> 63.2 mm. false: every run is taken for still (`meadow capture --assume-still`).
    bool checkMotion = true;
    capture::MotionParams motion;
    std::filesystem::path debugDir;  // overlay PNG per segmentation when not empty
};

struct CaptureSummary {
    int framesRead = 0;
    int segmentations = 0;
    int bladesFound = 0;
    int bladesModelled = 0;                // observations behind the library's archetypes
    int averagedArchetypes = 0;            // archetypes fitted to two or more observations
    int emptySegmentations = 0;            // segmentations that found no blade
    int motionTests = 0;                   // runs tested for motion (CaptureOptions::checkMotion)
    int movingRuns = 0;                    // of them, runs in which the tuft moved
    std::string motion;                    // the first moving run's measurement, for the CLI
    std::map<std::string, int> skippedBy;  // flag name -> blades it kept from modelling
    std::vector<std::string> notes;        // one line per skipped blade or empty segmentation
};

// What the blades were skipped as, with counts, and what to do about blades too thin to model
// ("" when none was skipped): "skipped as too-thin (5), overlapping (3); blades under ~3 px
// wide: bring the camera closer ... or pass --keep-flagged to model them anyway".
std::string skippedSummary(const CaptureSummary& summary);

struct CaptureResult {
    ArchetypeLibrary library;
    CaptureSummary summary;
};

// Whether a segmenter flag keeps captureArchetypes from modelling the blade (unless
// CaptureOptions::keepFlagged): after it the contour does not describe one whole blade.
// Asymmetry does not: the fit measures and records it.
bool disqualifiesFromModelling(capture::BladeFlag flag);

using CaptureProgress = std::function<void(int framesDone, int framesTotal)>;

// How many frames captureArchetypes segments at a time: recurringFrames rounded up to whole
// groups of fusionFrames (fusionFrames when recurringFrames is 0). The recurring readings of such
// a run are taken over its last that many frames, and only when the source held at least
// recurringFrames frames by then.
int segmentationWindow(const CaptureOptions& options);
// The recurring readings captureArchetypes gives the groups of a run, taken over `lastFrames`
// (the last segmentationWindow frames read, or all of them when fewer): empty when
// recurringFrames is 0 or lastFrames holds fewer frames than it.
capture::RecurringReadings recurringReadingsOfRun(const CaptureOptions& options,
                                                  std::span<const capture::DepthFrame> lastFrames);

// Throws ModelingError when no blade could be modelled (the message carries the reasons), and
// the source's CaptureError for unreadable input.
CaptureResult captureArchetypes(capture::DepthSource& source, const std::string& sourceName,
                                const CaptureOptions& options,
                                const CaptureProgress& progress = {});

}  // namespace meadow::modeling
