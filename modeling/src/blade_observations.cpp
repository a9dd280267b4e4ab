#include "meadow/modeling/blade_observations.h"

#include <algorithm>
#include <cstdio>

#include "meadow/modeling/error.h"

namespace meadow::modeling {

namespace {

std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& l : lines) out += (out.empty() ? "" : "; ") + l;
    return out;
}

std::string overlayName(int frameIndex) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%06d.png", frameIndex);
    return name;
}

// How the notes name a blade: "frame 3 blade 2".
std::string bladeName(int frame, int bladeId) {
    return "frame " + std::to_string(frame) + " blade " + std::to_string(bladeId);
}

// Why `a` is a piece of a leaf rather than a blade ("" when it is blade-shaped): its length along
// the spine under `minLengthToWidth` times its widest width.
std::string tooShortForItsWidth(const Archetype& a, float minLengthToWidth) {
    if (!(minLengthToWidth > 0.f)) return {};
    const float widest = a.width.maxWidth_m();
    const float length = a.height_m();
    if (length >= minLengthToWidth * widest) return {};
    char why[160];
    std::snprintf(why, sizeof why,
                  "%s: %.0f mm long and %.0f mm wide, under %g times its width: a piece of a leaf, "
                  "not a whole blade",
                  kTooShortForItsWidth, length * 1e3f, widest * 1e3f,
                  static_cast<double>(minLengthToWidth));
    return why;
}

}  // namespace

void observeGroup(const capture::GroupSegmentation& group, const CaptureOptions& options,
                  BladeObservations& observations, CaptureSummary& summary) {
    const capture::Segmentation& seg = group.segmentation;
    // The fit reads depth from one frame: the group's median when fused would be better, but
    // the first frame keeps each archetype traceable to a recorded frame.
    const capture::DepthFrame& depthFrame = group.frames.front();
    const int frameIndex = depthFrame.index;
    ++summary.segmentations;
    for (const capture::StageReport& stage : seg.report)
        summary.stage_ms[stage.stage] += stage.time_ms;
    if (group.moving) observations.movingGroups.insert(group.group);
    if (group.runMoved && summary.motion.empty()) summary.motion = group.runMoved->measurement;
    if (group.runMoved) {
        summary.turningRuns += group.runMoved->turning;
        summary.notes.push_back("frames " + std::to_string(group.runMoved->firstFrame) + "-" +
                                std::to_string(group.runMoved->lastFrame) + ": the tuft moved (" +
                                group.runMoved->measurement +
                                "): segmented frame by frame without recurring readings" +
                                (group.runMoved->turning ? ", as views of a turning plant"
                                                         : ", one archetype per group"));
    }
    if (!options.debugDir.empty())
        capture::writeDebugOverlay(options.debugDir / overlayName(frameIndex), depthFrame, seg);
    summary.emptySegmentations += seg.empty();
    if (seg.noPlant) {
        ++summary.noPlantSegmentations;
        if (summary.noPlant.empty()) summary.noPlant = seg.noBladesReason;
    }
    if (seg.empty())
        summary.notes.push_back("frame " + std::to_string(frameIndex) + ": no blades (" +
                                seg.noBladesReason + ")");
    for (std::size_t index = 0; index < seg.blades.size(); ++index) {
        const capture::BladeContour& blade = seg.blades[index];
        ++summary.bladesFound;
        const std::string where = bladeName(frameIndex, blade.id);
        const bool flagged =
            std::any_of(blade.flags.begin(), blade.flags.end(), disqualifiesFromModelling);
        if (flagged && !options.keepFlagged) {
            for (const capture::BladeFlag flag : blade.flags)
                if (disqualifiesFromModelling(flag)) ++summary.skippedBy[capture::toString(flag)];
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
            observations.skeletons.push_back({group.group, std::move(skeleton)});
            observations.views.push_back({{frameIndex, blade.id},
                                          blade.reasons,
                                          blade.mask,
                                          blade.maskOrigin_px,
                                          depthFrame.intrinsics});
        } catch (const ModelingError& e) {
            summary.notes.push_back(where + " not modelled: " + e.what());
        }
    }
}

std::vector<std::vector<std::size_t>> trackObservations(const BladeObservations& observations,
                                                        const BladeTrackParams& params) {
    std::vector<std::vector<std::size_t>> tracks;
    for (std::vector<std::size_t>& track : trackBlades(observations.skeletons, params)) {
        const bool anyMoving = std::any_of(track.begin(), track.end(), [&](std::size_t i) {
            return observations.movingGroups.contains(observations.skeletons[i].group);
        });
        if (!anyMoving) {
            tracks.push_back(std::move(track));
            continue;
        }
        for (const std::size_t i : track) tracks.push_back({i});
    }
    return tracks;
}

std::vector<TrackFit> fitTracks(const BladeObservations& observations,
                                const std::vector<std::vector<std::size_t>>& tracks,
                                const CaptureOptions& options, const std::string& sourceName,
                                CaptureSummary& summary) {
    std::vector<TrackFit> fits;
    for (const std::vector<std::size_t>& track : tracks) {
        const BladeView& first = observations.views[track.front()];
        Source src{sourceName, first.sighting.frame, first.sighting.bladeId, {}, {}};
        for (const std::size_t i : track) {
            src.seenIn.push_back(observations.views[i].sighting);
            for (const std::string& flag : observations.views[i].flags)
                if (std::find(src.flags.begin(), src.flags.end(), flag) == src.flags.end())
                    src.flags.push_back(flag);
        }
        try {
            // Named f<frame>-b<blade> by its first view; the distance-transform width check reads
            // that view's mask.
            BladeFit fit =
                fitArchetype(trackSkeleton(observations.skeletons, track, options.tracks),
                             options.fit, src, first.mask, &first.intrinsics, first.maskOrigin_px);
            if (const std::string why =
                    tooShortForItsWidth(fit.archetype, options.minLengthToWidth);
                !why.empty()) {
                if (!options.keepFlagged) {
                    summary.skippedBy[kTooShortForItsWidth] += static_cast<int>(track.size());
                    summary.notes.push_back(bladeName(src.frame, src.bladeId) + " skipped: " + why);
                    continue;
                }
                fit.archetype.source.flags.push_back(why);
            }
            fits.push_back({std::move(fit), track});
            summary.bladesModelled += static_cast<int>(track.size());
            summary.averagedArchetypes += track.size() > 1;
        } catch (const ModelingError& e) {
            summary.notes.push_back(bladeName(src.frame, src.bladeId) + " (seen in " +
                                    std::to_string(track.size()) +
                                    " group(s)) not modelled: " + e.what());
        }
    }
    return fits;
}

}  // namespace meadow::modeling
