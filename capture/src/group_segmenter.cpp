#include "meadow/capture/group_segmenter.h"

#include <algorithm>
#include <optional>
#include <span>

#include "meadow/capture/error.h"

namespace meadow::capture {

std::string GroupingParams::problem() const {
    if (fusionFrames < 1) return "fusionFrames must be >= 1, got " + std::to_string(fusionFrames);
    if (recurringFrames < 0)
        return "recurringFrames must be >= 0, got " + std::to_string(recurringFrames);
    if (std::string why = recurring.problem(); !why.empty()) return why;
    return motion.problem();
}

int GroupingParams::window() const {
    const int fusion = std::max(1, fusionFrames);
    return recurringFrames > 0 ? (recurringFrames + fusion - 1) / fusion * fusion : fusion;
}

GroupSegmenter::GroupSegmenter(const Segmenter& segmenter, GroupingParams params)
    : segmenter_(segmenter), params_(std::move(params)) {
    if (const std::string why = params_.problem(); !why.empty())
        throw CaptureError("GroupSegmenter: " + why);
}

std::vector<GroupSegmentation> GroupSegmenter::add(DepthFrame frame) {
    recent_.push_back(std::move(frame));
    if (static_cast<int>(recent_.size()) > params_.window()) recent_.erase(recent_.begin());
    if (static_cast<int>(++pending_) < params_.window()) return {};
    return segmentPending();
}

std::vector<GroupSegmentation> GroupSegmenter::finish() { return segmentPending(); }

RecurringReadings GroupSegmenter::recurringOfRun(const std::vector<DepthFrame>& run) const {
    if (params_.recurringFrames <= 0 ||
        run.size() < static_cast<std::size_t>(params_.recurringFrames))
        return {};
    return recurringReadings(run, params_.recurring);
}

std::vector<GroupSegmentation> GroupSegmenter::segmentPending() {
    std::vector<GroupSegmentation> out;
    if (pending_ == 0) return out;
    const std::vector<DepthFrame>& run = recent_;
    // A turning plant's frames are segmented alone, without recurring readings.
    bool moving = params_.turning, turning = params_.turning;
    RecurringReadings tips = moving ? RecurringReadings{} : recurringOfRun(run);
    const auto fusion = static_cast<std::size_t>(params_.fusionFrames);
    const std::size_t firstPending = run.size() - pending_;
    std::size_t step = moving ? 1 : fusion;
    for (std::size_t first = firstPending; first < run.size(); first += step) {
        const auto groupOf = [&](std::size_t frames) {
            return std::span<const DepthFrame>(run).subspan(first,
                                                            std::min(frames, run.size() - first));
        };
        std::span<const DepthFrame> group = groupOf(step);
        GroupSegmentation g;
        g.segmentation = segmenter_.segment(group, tips);
        // The run's first segmentation gives the tuft's band to test the run for motion in, and
        // its first frame alone the plant's pixels: fused, a turning plant's frames keep only
        // what they share (its stem and pot), which changes least.
        if (first == firstPending && params_.checkMotion && !moving && !tips.depth_mm.empty() &&
            g.segmentation.farDepth_m > g.segmentation.nearDepth_m) {
            // Segmented as a moving run's frames are: alone, without recurring readings.
            std::optional<Segmentation> firstAlone;
            if (group.size() > 1) firstAlone = segmenter_.segment(groupOf(1), RecurringReadings{});
            const TuftMotion motion = tuftMotion(
                run, g.segmentation.nearDepth_m, g.segmentation.farDepth_m, params_.motion,
                firstAlone ? firstAlone->clusterMask : g.segmentation.clusterMask);
            motionTests_ += motion.measured;
            if (motion.moved(params_.motion)) {
                moving = true;
                turning = motion.turned(params_.motion);
                ++movingRuns_;
                g.runMoved = MovingRun{run.front().index, run.back().index,
                                       motion.summary(params_.motion), turning};
                // Frames that disagree are never fused, nor their readings taken as recurring:
                // each frame of the run is segmented alone.
                tips = {};
                step = 1;
                group = groupOf(step);
                g.segmentation =
                    firstAlone ? std::move(*firstAlone) : segmenter_.segment(group, tips);
            }
        }
        g.group = groups_++;
        g.moving = moving;
        g.turning = turning;
        g.frames.assign(group.begin(), group.end());
        out.push_back(std::move(g));
    }
    pending_ = 0;
    return out;
}

}  // namespace meadow::capture
