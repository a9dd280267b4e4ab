#include "meadow/modeling/capture_pipeline.h"

#include <algorithm>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include "meadow/modeling/archetype_merge.h"
#include "meadow/modeling/blade_observations.h"
#include "meadow/modeling/error.h"
#include "meadow/modeling/stem_height.h"

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

// Why nothing was modelled, in one bounded line: a long recording skips thousands of blades,
// so the message counts the flags and quotes only the first few notes.
std::string noBladeModelledMessage(const std::string& sourceName, const CaptureSummary& summary) {
    constexpr std::size_t kQuotedNotes = 3;
    if (summary.segmentations > 0 && summary.noPlantSegmentations == summary.segmentations) {
        constexpr std::string_view kPrefix = "no plant in view: ";
        const std::string why = summary.noPlant.starts_with(kPrefix)
                                    ? summary.noPlant.substr(kPrefix.size())
                                    : summary.noPlant;
        return "capture: no plant in " + sourceName + ": " + why +
               "; aim the camera at the plant, or give its depth band with --near/--far";
    }
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

// How many frames to read: the source's count, capped by maxFrames (0 or less: unknown).
int framesToRead(const capture::DepthSource& source, int maxFrames) {
    const int total = source.info().frameCount;
    if (maxFrames <= 0) return total;
    return total > 0 ? std::min(total, maxFrames) : maxFrames;
}

// A turning plant's archetypes that no other view shows are pieces of leaves or false blades
// (ViewJoinResult::seenOnce): left out and noted, or flagged with keepFlagged.
void leaveOutSeenOnce(const std::vector<std::size_t>& seenOnce, bool keepFlagged,
                      std::vector<Archetype>& archetypes, CaptureSummary& summary) {
    const std::string why =
        std::string(kSeenOnce) + ": no other view of the turning plant shows a leaf along it";
    for (const std::size_t i : seenOnce) {
        if (keepFlagged) {
            archetypes[i].source.flags.push_back(why);
            continue;
        }
        ++summary.skippedBy[kSeenOnce];
        --summary.bladesModelled;  // a turning plant's archetype is one view's blade
        summary.notes.push_back(archetypes[i].name + " skipped: " + why);
    }
    if (keepFlagged) return;
    // seenOnce ascends: erased from the back, the indices before stay valid.
    for (auto i = seenOnce.rbegin(); i != seenOnce.rend(); ++i)
        archetypes.erase(archetypes.begin() + static_cast<std::ptrdiff_t>(*i));
}

// What became of the turntable's ends, for --verbose ("" when not tried).
std::string loopNote(const capture::LoopClosure& loop) {
    if (loop.lastFrame < 0) return {};
    if (!loop.why.empty()) return "the turntable's ends: " + loop.why;
    std::ostringstream note;
    note.precision(1);
    note << std::fixed << "frame " << loop.lastFrame << " registered to frame " << loop.firstFrame
         << " too: ";
    if (loop.joinedChains) note << "its chain joined that frame's";
    if (loop.closed)
        note << "the chain's loop closed, " << loop.drift_deg << " deg and " << loop.drift_mm
             << " mm of drift spread over its views";
    return note.str();
}

// Notes each registered view's turn, or why it starts a chain, and joins each leaf's archetypes.
void joinTurningViews(const CaptureOptions& options, CaptureResult& result) {
    CaptureSummary& summary = result.summary;
    const std::vector<capture::RegisteredView>& views = result.turningViews;
    summary.turningViews = static_cast<int>(views.size());
    std::set<int> chains;
    for (const capture::RegisteredView& v : views) chains.insert(v.chain);
    summary.viewChains = static_cast<int>(chains.size());
    for (std::size_t i = 1; i < views.size(); ++i) {
        const capture::RegisteredView& v = views[i];
        const std::string frame = "frame " + std::to_string(v.frame);
        if (!v.why.empty()) {
            summary.notes.push_back(frame + ": not registered to frame " +
                                    std::to_string(views[i - 1].frame) + ": " + v.why);
            continue;
        }
        ++summary.registeredViews;
        std::ostringstream note;
        note.precision(0);
        note << std::fixed << frame << ": turned " << v.turn_deg << " deg from frame "
             << v.registeredTo << ", " << v.inlierShare * 100.f
             << " % of its plant readings on that frame's";
        summary.notes.push_back(note.str());
    }
    if (const std::string note = loopNote(result.turningLoop); !note.empty())
        summary.notes.push_back(note);
    const ViewJoinResult joined =
        joinSameLeafAcrossViews(result.library.archetypes, views, options.joining);
    summary.joinedArchetypes = joined.leftOut;
    leaveOutSeenOnce(joined.seenOnce, options.keepFlagged, result.library.archetypes, summary);
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
        m += "; blades under ~3 px wide: bring the camera closer (docs/capture.md, \"Capturing "
             "your own plant\") or pass --keep-flagged to model them anyway";
    return m;
}

CaptureResult captureArchetypes(capture::DepthSource& source, const std::string& sourceName,
                                const CaptureOptions& options, const CaptureProgress& progress) {
    const capture::Segmenter segmenter(options.segmenter);
    capture::GroupSegmenter groups(segmenter, options.groups);
    CaptureResult result;
    result.library.generator = "meadow capture 0.1.0";
    result.library.source = sourceName;
    CaptureSummary& summary = result.summary;

    BladeObservations observations;
    std::vector<float> stemHeights_m;
    // A turning plant's views (--turntable, or a run the motion test found turning) are
    // registered as they come, each to the ones before: the work is spread over the frames'
    // progress, and only the last few views' clouds are kept. The registrar starts with the
    // first such view (it quiets PCL's console for the whole run).
    std::optional<capture::ViewRegistrar> registrar;
    const auto observe = [&](const std::vector<capture::GroupSegmentation>& segmented) {
        for (const capture::GroupSegmentation& group : segmented) {
            observeGroup(group, options, observations, summary);
            if (options.tracks.enabled && group.turning) {
                if (!registrar) registrar.emplace(options.registration);
                registrar->add(capture::plantCloud(group.segmentation, group.frames.front()));
            }
            if (const auto height = stemHeight_m(group.segmentation, group.frames.front()))
                stemHeights_m.push_back(*height);
        }
    };
    const int total = framesToRead(source, options.maxFrames);
    while (total <= 0 || summary.framesRead < total) {
        std::optional<capture::DepthFrame> frame = source.next();
        if (!frame) break;
        if (const std::string why = capture::implausibleDepthProblem(*frame); !why.empty())
            throw ModelingError("capture: " + sourceName + " " + why);
        ++summary.framesRead;
        observe(groups.add(std::move(*frame)));
        if (progress) progress(summary.framesRead, std::max(total, summary.framesRead));
    }
    observe(groups.finish());
    result.library.stem = stemOf(std::move(stemHeights_m));
    summary.motionTests = groups.motionTests();
    summary.movingRuns = groups.movingRuns();

    for (TrackFit& fitted : fitTracks(observations, trackObservations(observations, options.tracks),
                                      options, sourceName, summary))
        result.library.archetypes.push_back(std::move(fitted.fit.archetype));

    if (registrar) {
        result.turningLoop = registrar->closeLoop();
        result.turningViews = registrar->views();
    }
    if (result.turningViews.size() >= 2) joinTurningViews(options, result);

    if (summary.framesRead == 0) throw ModelingError("capture: " + sourceName + " has no frames");
    if (result.library.archetypes.empty())
        throw ModelingError(noBladeModelledMessage(sourceName, summary));
    if (options.maxArchetypes > 0) mergeNearDuplicates(result.library, options.maxArchetypes);
    return result;
}

}  // namespace meadow::modeling
