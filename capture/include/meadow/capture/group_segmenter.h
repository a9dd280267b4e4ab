#pragma once
// Capture's multi-frame work: frames, one at a time, become fused groups and one segmentation
// per group. Frames are read a window at a time (recurringFrames rounded up to whole groups of
// fusionFrames). Each window is a run: its readings that recur over it are found
// (recurring_readings.h) and given to every group's tip trails, after the run has been tested
// for motion (tuft_motion.h): a tuft that moved breaks what recurring readings assume, so a
// moving run is segmented without them and its groups say so. Groups are fused by the
// segmenter's fusion method and segmented (segmenter.h).
#include <optional>
#include <string>
#include <vector>

#include "meadow/capture/depth_frame.h"
#include "meadow/capture/recurring_readings.h"
#include "meadow/capture/segmenter.h"
#include "meadow/capture/tuft_motion.h"

namespace meadow::capture {

struct GroupingParams {
    int fusionFrames = 3;  // frames fused per segmentation; 1 = every frame on its own
    // Tip trails also follow readings that recur over this many frames of a still tuft, taken
    // over the last recurringFrames frames of each run (rounded up to whole groups); fewer
    // frames in all, or 0: each group's trails see its own readings only.
    int recurringFrames = 12;
    RecurringParams recurring;
    bool checkMotion = true;  // false: every run is taken for still
    // Every frame is a view of a turning plant (a turntable): segmented alone, as a moving run's
    // frames are, without the motion test.
    bool turning = false;
    MotionParams motion;

    // Empty when usable; otherwise what is wrong.
    [[nodiscard]] std::string problem() const;
    // Frames segmented at a time: recurringFrames rounded up to whole groups of fusionFrames
    // (fusionFrames when recurringFrames is 0).
    [[nodiscard]] int window() const;
};

// A run of frames in which the tuft moved (found by the motion test).
struct MovingRun {
    int firstFrame = 0, lastFrame = 0;  // frame indices
    std::string measurement;            // TuftMotion::summary
    bool turning = false;               // its plant turned (TuftMotion::turned), not swayed
};

struct GroupSegmentation {
    int group = 0;                   // 0, 1, ... in the order segmented
    std::vector<DepthFrame> frames;  // the group's frames; the first is the one a fit reads
    Segmentation segmentation;
    bool moving = false;  // its run moved: segmented without recurring readings
    // Its frame is a view of a turning plant: GroupingParams::turning, or its run moved as a
    // turning plant's views do (MovingRun::turning). Such views are registered to one another.
    bool turning = false;
    std::optional<MovingRun> runMoved;  // on the group whose segmentation found its run moving
};

// Feed frames with add(); each completed window returns its groups' segmentations, and
// finish() segments the frames left over. Throws CaptureError for unusable parameters.
class GroupSegmenter {
public:
    GroupSegmenter(const Segmenter& segmenter, GroupingParams params);

    [[nodiscard]] std::vector<GroupSegmentation> add(DepthFrame frame);
    [[nodiscard]] std::vector<GroupSegmentation> finish();

    [[nodiscard]] int motionTests() const { return motionTests_; }  // runs the test measured
    [[nodiscard]] int movingRuns() const { return movingRuns_; }
    [[nodiscard]] const GroupingParams& params() const { return params_; }

private:
    [[nodiscard]] std::vector<GroupSegmentation> segmentPending();
    // The run's recurring readings: empty when recurringFrames is 0 or the run is shorter.
    [[nodiscard]] RecurringReadings recurringOfRun(const std::vector<DepthFrame>& run) const;

    const Segmenter& segmenter_;
    GroupingParams params_;
    std::vector<DepthFrame> recent_;  // the last window() frames read
    std::size_t pending_ = 0;         // of them, not yet segmented
    int groups_ = 0;
    int motionTests_ = 0;
    int movingRuns_ = 0;
};

}  // namespace meadow::capture
