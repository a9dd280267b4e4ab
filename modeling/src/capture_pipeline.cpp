#include "meadow/modeling/capture_pipeline.h"

#include <algorithm>
#include <cstdio>
#include <deque>
#include <set>

#include "meadow/modeling/archetype_merge.h"
#include "meadow/modeling/error.h"

namespace meadow::modeling {

// The fit would model something that is not there (capture_pipeline.h).
bool disqualifiesFromModelling(capture::BladeFlag flag) {
    switch (flag) {
        case capture::BladeFlag::Overlapping:
        case capture::BladeFlag::CurlsSideways:
        case capture::BladeFlag::TooThin:
        case capture::BladeFlag::BaseHidden:
        case capture::BladeFlag::Truncated:
            return true;
        case capture::BladeFlag::Asymmetric:
            return false;
    }
    return true;
}

namespace {

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines) out += (out.empty() ? "" : "; ") + l;
    return out;
}

// Why nothing was modelled, in one bounded line: a long recording skips thousands of blades,
// so the message counts the flags and quotes only the first few notes.
std::string noBladeModelledMessage(const std::string& sourceName, const CaptureSummary& summary) {
    constexpr std::size_t kQuotedNotes = 3;
    std::string m = "capture: no blade of " + sourceName +
                    " could be modelled: " + std::to_string(summary.bladesFound) + " found in " +
                    std::to_string(summary.segmentations) + " segmentation(s)";
    if (summary.emptySegmentations > 0)
        m += ", " + std::to_string(summary.emptySegmentations) + " segmentation(s) without blades";
    if (const std::string skipped = skippedSummary(summary); !skipped.empty()) m += "; " + skipped;
    for (std::size_t i = 0; i < std::min(kQuotedNotes, summary.notes.size()); ++i)
        m += (i == 0 ? "; " : " | ") + summary.notes[i];
    if (summary.notes.size() > kQuotedNotes)
        m += " | and " + std::to_string(summary.notes.size() - kQuotedNotes) + " more";
    return m + "; check the depth band (--near/--far) or use --debug DIR to see the masks";
}

// What fitting a tracked blade needs of each observation besides its skeleton.
struct Observed {
    BladeSighting sighting;
    std::vector<std::string> flags;  // the segmenter's reason lines
    cv::Mat1b mask;
    cv::Point maskOrigin_px;
    capture::Intrinsics intrinsics;
};

std::string frameName(int index) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", index);
    return name;
}

}  // namespace

std::string skippedSummary(const CaptureSummary& summary) {
    if (summary.skippedBy.empty()) return {};
    std::string m = "skipped as";
    const char* separator = " ";
    for (const auto& [flag, count] : summary.skippedBy) {
        m += separator + flag + " (" + std::to_string(count) + ")";
        separator = ", ";
    }
    if (summary.skippedBy.contains(capture::toString(capture::BladeFlag::TooThin)))
        m += "; blades under ~3 px wide: bring the camera closer (slim grass: recall 0.4-0.5 "
             "from 0.5 m, 0.24 from 0.8 m) or pass --keep-flagged to model them anyway";
    return m;
}

int segmentationWindow(const CaptureOptions& options) {
    const int fusion = std::max(1, options.fusionFrames);
    return options.recurringFrames > 0 ? (options.recurringFrames + fusion - 1) / fusion * fusion
                                       : fusion;
}

capture::RecurringReadings recurringReadingsOfRun(const CaptureOptions& options,
                                                  std::span<const capture::DepthFrame> lastFrames) {
    if (options.recurringFrames <= 0 ||
        lastFrames.size() < static_cast<std::size_t>(options.recurringFrames))
        return {};
    return capture::recurringReadings(lastFrames, options.recurring);
}

CaptureResult captureArchetypes(capture::DepthSource& source, const std::string& sourceName,
                                const CaptureOptions& options, const CaptureProgress& progress) {
    if (options.fusionFrames < 1)
        throw std::invalid_argument("captureArchetypes: fusionFrames must be >= 1");
    if (options.recurringFrames < 0)
        throw std::invalid_argument("captureArchetypes: recurringFrames must be >= 0");
    if (const std::string why = options.recurring.problem(); !why.empty())
        throw std::invalid_argument("captureArchetypes: " + why);
    const capture::Segmenter segmenter(options.segmenter);
    CaptureResult result;
    result.library.generator = "meadow capture 0.1.0";
    result.library.source = sourceName;
    CaptureSummary& summary = result.summary;

    int total = source.info().frameCount;
    if (options.maxFrames > 0)
        total = total > 0 ? std::min(total, options.maxFrames) : options.maxFrames;

    // Every trustworthy blade of every group, as a skeleton; fitted once per track at the end.
    std::vector<BladeObservation> observations;
    std::vector<Observed> observed;  // parallel: what the fit needs beyond the skeleton
    // Frames are segmented a window at a time: groups of fusionFrames, whose tip trails also
    // see the readings that recur over the window (when it is long enough).
    const int window = segmentationWindow(options);
    std::deque<capture::DepthFrame> recent;  // the last `window` frames read
    std::size_t pending = 0;                 // of them, not yet segmented
    std::span<const capture::DepthFrame> group;
    capture::RecurringReadings tips;
    std::set<int> movingGroups;  // groups of runs in which the tuft moved: not tracked
    bool moving = false;         // the run being segmented moved
    const auto processGroup = [&](const capture::Segmentation& seg) {
        const int groupIndex = summary.segmentations++;
        if (moving) movingGroups.insert(groupIndex);
        const int frameIndex = group.front().index;
        if (!options.debugDir.empty())
            capture::writeDebugOverlay(options.debugDir / frameName(frameIndex), group.front(),
                                       seg);
        summary.emptySegmentations += seg.empty();
        if (seg.empty())
            summary.notes.push_back("frame " + std::to_string(frameIndex) + ": no blades (" +
                                    seg.noBladesReason + ")");
        // The fit reads depth from one frame: the group's median when fused would be better,
        // but the first frame keeps each archetype traceable to a recorded frame.
        const capture::DepthFrame& depthFrame = group.front();
        for (std::size_t index = 0; index < seg.blades.size(); ++index) {
            const capture::BladeContour& blade = seg.blades[index];
            ++summary.bladesFound;
            const std::string where =
                "frame " + std::to_string(frameIndex) + " blade " + std::to_string(blade.id);
            const bool flagged =
                std::any_of(blade.flags.begin(), blade.flags.end(), disqualifiesFromModelling);
            if (flagged && !options.keepFlagged) {
                for (const capture::BladeFlag flag : blade.flags)
                    if (disqualifiesFromModelling(flag))
                        ++summary.skippedBy[capture::toString(flag)];
                summary.notes.push_back(where + " skipped: " + joined(blade.reasons));
                continue;
            }
            try {
                // Rooted at the tuft's base (options.fit.root); a refusal is noted, not fatal.
                Skeleton skeleton = segmentedBladeSkeleton(seg, index, depthFrame, options.fit);
                if (skeleton.baseNotRooted)
                    for (const std::string& reason : skeleton.reasons)
                        if (reason.starts_with("not rooted"))
                            summary.notes.push_back(where + " modelled unrooted: " + reason);
                observations.push_back({groupIndex, std::move(skeleton)});
                observed.push_back({{frameIndex, blade.id},
                                    blade.reasons,
                                    blade.mask,
                                    blade.maskOrigin_px,
                                    depthFrame.intrinsics});
            } catch (const ModelingError& e) {
                summary.notes.push_back(where + " not modelled: " + e.what());
            }
        }
    };
    const auto processPending = [&] {
        if (pending == 0) return;
        const std::vector<capture::DepthFrame> frames(recent.begin(), recent.end());
        tips = recurringReadingsOfRun(options, frames);
        moving = false;
        const auto fusion = static_cast<std::size_t>(options.fusionFrames);
        for (std::size_t first = frames.size() - pending; first < frames.size(); first += fusion) {
            group = std::span<const capture::DepthFrame>(frames).subspan(
                first, std::min(fusion, frames.size() - first));
            capture::Segmentation seg = segmenter.segment(group, tips);
            // The run's first segmentation gives the tuft's band to test the run for motion in.
            if (first == frames.size() - pending && options.checkMotion && !tips.depth_mm.empty() &&
                seg.farDepth_m > seg.nearDepth_m) {
                const capture::TuftMotion motion =
                    capture::tuftMotion(frames, seg.nearDepth_m, seg.farDepth_m, options.motion);
                summary.motionTests += motion.measured;
                if (motion.moved(options.motion)) {
                    moving = true;
                    ++summary.movingRuns;
                    const std::string what = motion.summary(options.motion);
                    if (summary.motion.empty()) summary.motion = what;
                    summary.notes.push_back(
                        "frames " + std::to_string(frames.front().index) + "-" +
                        std::to_string(frames.back().index) + ": the tuft moved (" + what +
                        "): segmented without recurring readings, one archetype per group");
                    tips = {};
                    seg = segmenter.segment(group, tips);
                }
            }
            processGroup(seg);
        }
        group = {};
        pending = 0;
    };

    while (total <= 0 || summary.framesRead < total) {
        auto frame = source.next();
        if (!frame) break;
        ++summary.framesRead;
        recent.push_back(std::move(*frame));
        if (static_cast<int>(recent.size()) > window) recent.pop_front();
        if (static_cast<int>(++pending) == window) processPending();
        if (progress) progress(summary.framesRead, std::max(total, summary.framesRead));
    }
    processPending();

    // A track that holds a view from a run in which the tuft moved is one archetype per view:
    // the mean of a moving blade's views is no view of it.
    std::vector<std::vector<std::size_t>> tracks;
    for (std::vector<std::size_t>& track : trackBlades(observations, options.tracks)) {
        const bool anyMoving = std::any_of(track.begin(), track.end(), [&](std::size_t i) {
            return movingGroups.contains(observations[i].group);
        });
        if (!anyMoving) {
            tracks.push_back(std::move(track));
            continue;
        }
        for (const std::size_t i : track) tracks.push_back({i});
    }
    for (const std::vector<std::size_t>& track : tracks) {
        const Observed& first = observed[track.front()];
        Source src{sourceName, first.sighting.frame, first.sighting.bladeId, {}, {}};
        for (const std::size_t i : track) {
            src.seenIn.push_back(observed[i].sighting);
            for (const std::string& flag : observed[i].flags)
                if (std::find(src.flags.begin(), src.flags.end(), flag) == src.flags.end())
                    src.flags.push_back(flag);
        }
        try {
            // Named f<frame>-b<blade> by its first view; the distance-transform width check reads
            // that view's mask.
            BladeFit fit =
                fitArchetype(trackSkeleton(observations, track, options.tracks), options.fit, src,
                             first.mask, &first.intrinsics, first.maskOrigin_px);
            result.library.archetypes.push_back(std::move(fit.archetype));
            summary.bladesModelled += static_cast<int>(track.size());
            summary.averagedArchetypes += track.size() > 1;
        } catch (const ModelingError& e) {
            summary.notes.push_back("frame " + std::to_string(src.frame) + " blade " +
                                    std::to_string(src.bladeId) + " (seen in " +
                                    std::to_string(track.size()) +
                                    " group(s)) not modelled: " + e.what());
        }
    }

    if (summary.framesRead == 0) throw ModelingError("capture: " + sourceName + " has no frames");
    if (result.library.archetypes.empty())
        throw ModelingError(noBladeModelledMessage(sourceName, summary));
    if (options.maxArchetypes > 0) mergeNearDuplicates(result.library, options.maxArchetypes);
    return result;
}

}  // namespace meadow::modeling
