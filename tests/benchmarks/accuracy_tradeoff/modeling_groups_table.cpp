// 7. Modeling over fused groups: one archetype per blade, fitted to the mean of its skeletons
// over 1, 2, 4 and 8 groups of capture's fused frames (tables.h).
#include <cstdlib>
#include <glm/geometric.hpp>
#include <iostream>
#include <map>
#include <span>
#include <sstream>

#include "accuracy_tradeoff/blade_error.h"
#include "accuracy_tradeoff/report.h"
#include "accuracy_tradeoff/tables.h"
#include "meadow/modeling/blade_tracks.h"
#include "meadow/modeling/error.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;
using modeling::BladeFit;
using modeling::BladeObservation;
using modeling::CaptureOptions;

const std::vector<int> kGroupCounts{1, 2, 4, 8};

struct TrackedFit {
    BladeFit fit;
    int trueId = 0;  // the true blade most of the track's observations matched; 0: none
    int observations = 0;
};

// What capture sees of a scene's first `groups` fused groups: every trustworthy blade's skeleton
// (segmentedBladeSkeleton) and the true blade it matches (IoU, as the other tables match).
struct Observations {
    std::vector<BladeObservation> observations;
    std::vector<int> trueIds;
};

Observations observe(const capture::Segmenter& segmenter, const Scene& scene,
                     const CaptureOptions& options, int groups) {
    Observations out;
    const auto frames = static_cast<std::size_t>(options.fusionFrames);
    const auto window = static_cast<std::size_t>(modeling::segmentationWindow(options));
    const std::size_t read = static_cast<std::size_t>(groups) * frames;
    capture::RecurringReadings tips;
    for (int g = 0; g < groups; ++g) {
        const std::size_t first = static_cast<std::size_t>(g) * frames;
        // As captureArchetypes reads them: a window at a time, each window's groups with the
        // readings recurring over its last `window` frames.
        if (first % window == 0) {
            const std::size_t end = std::min(read, first + window);
            tips = modeling::recurringReadingsOfRun(
                options, std::span(scene.frames)
                             .subspan(end - std::min(end, window), std::min(end, window)));
        }
        const std::span<const capture::DepthFrame> group(scene.frames.data() + first, frames);
        const capture::Segmentation seg = segmenter.segment(group, tips);
        const BladeMatch match = matchBlades(scene.labels, seg.blades);
        for (std::size_t b = 0; b < seg.blades.size(); ++b) {
            const auto& flags = seg.blades[b].flags;
            if (std::any_of(flags.begin(), flags.end(), modeling::disqualifiesFromModelling))
                continue;
            try {
                out.observations.push_back(
                    {g, modeling::segmentedBladeSkeleton(seg, b, group.front(), options.fit)});
                out.trueIds.push_back(match.foundToTrueId[b]);
            } catch (const modeling::ModelingError&) {
            }
        }
    }
    return out;
}

// As modeling::captureArchetypes fits them: one archetype per track, to the mean of its
// skeletons; with tracks.enabled false, one per observation (`--per-group`).
std::vector<TrackedFit> fitTracks(const Observations& seen, const CaptureOptions& options,
                                  const modeling::BladeTrackParams& tracks) {
    std::vector<TrackedFit> out;
    for (const auto& track : modeling::trackBlades(seen.observations, tracks)) {
        std::map<int, int> votes;
        for (const std::size_t i : track) ++votes[seen.trueIds[i]];
        int trueId = seen.trueIds[track.front()];
        for (const auto& [id, n] : votes)
            if (n > votes[trueId]) trueId = id;
        try {
            out.push_back(
                {modeling::fitArchetype(modeling::trackSkeleton(seen.observations, track, tracks),
                                        options.fit),
                 trueId, static_cast<int>(track.size())});
        } catch (const modeling::ModelingError&) {
        }
    }
    return out;
}

// One way of fitting, pooled over a preset's tufts.
struct Pooled {
    std::vector<BladeError> errors;
    int archetypes = 0, observations = 0;
    double cpu_ms = 0.0;
    void add(const std::vector<TrackedFit>& fits, const Scene& scene, double fitCpu_ms) {
        archetypes += static_cast<int>(fits.size());
        cpu_ms += fitCpu_ms;
        for (const TrackedFit& f : fits) {
            observations += f.observations;
            if (f.trueId != 0)
                errors.push_back(bladeError(
                    f.fit, scene.tuft.blades.at(static_cast<std::size_t>(f.trueId - 1))));
        }
    }
    // "tip RMS (median)", "height mean abs", "width MAE" (blank when nothing matched).
    [[nodiscard]] std::vector<std::string> cells() const {
        std::vector<float> tip, tipSq, heightAbs, width;
        for (const BladeError& e : errors) {
            tip.push_back(e.v2_mm);
            tipSq.push_back(e.v2_mm * e.v2_mm);
            heightAbs.push_back(std::abs(e.heightError));
            width.push_back(e.widthMaeFraction);
        }
        return {orBlank(tip, std::sqrt(mean(tipSq)), 2), orBlank(tip, median(tip), 2),
                orBlank(tip, kPercent * mean(heightAbs), 2),
                orBlank(tip, kPercent * mean(width), 2)};
    }
};

}  // namespace

void modelingOverGroups(const Plan& plan, const fs::path& out) {
    const int mostGroups = kGroupCounts.back();
    const CaptureOptions options{};
    const capture::Segmenter segmenter(options.segmenter);
    std::cout << "modeling over fused groups: " << plan.bladeTypes.size() << " presets x "
              << plan.distances_m.size() << " distances x " << plan.modelingSeeds << " seeds, 1-"
              << mostGroups << " groups of " << options.fusionFrames << " frames\n";
    std::ostringstream csv, md;
    csv << "preset,groups,frames,true_blades,mode,archetypes,archetypes_matched,"
           "observations_per_archetype,tip_rms_mm,tip_median_mm,height_error_abs_pct,"
           "width_mae_pct_of_max,cpu_ms_per_tuft\n";
    md << "| preset | groups (frames) | archetypes (matched): per group / one per blade | tip RMS "
          "(median) (mm): per group / one per blade | height error: per group / one per blade | "
          "width MAE (% of max): per group / one per blade | CPU per tuft (ms): per group / one "
          "per blade |\n|---|---|---|---|---|---|---|\n";
    modeling::BladeTrackParams perGroup = options.tracks;
    perGroup.enabled = false;
    for (const std::string& preset : plan.bladeTypes) {
        std::vector<Scene> scenes;
        for (float distance_m : plan.distances_m)
            for (int seed = 1; seed <= plan.modelingSeeds; ++seed)
                scenes.push_back(renderScene(preset, kNominalNoise,
                                             static_cast<std::uint64_t>(seed), distance_m,
                                             mostGroups * options.fusionFrames));
        for (const int groups : kGroupCounts) {
            Pooled single, tracked;
            int trueBlades = 0;
            for (const Scene& scene : scenes) {
                trueBlades += static_cast<int>(scene.tuft.blades.size());
                Observations seen;
                const double seeing_ms = timeMedian(1, [&] {
                                             seen = observe(segmenter, scene, options, groups);
                                         }).cpu_ms;
                std::vector<TrackedFit> fits;
                const double single_ms =
                    timeMedian(1, [&] { fits = fitTracks(seen, options, perGroup); }).cpu_ms;
                single.add(fits, scene, seeing_ms + single_ms);
                const double tracked_ms =
                    timeMedian(1, [&] { fits = fitTracks(seen, options, options.tracks); }).cpu_ms;
                tracked.add(fits, scene, seeing_ms + tracked_ms);
            }
            const auto tuftMs = [&](const Pooled& p) {
                return p.cpu_ms / static_cast<double>(scenes.size());
            };
            const auto perArchetype = [](const Pooled& p) {
                return p.archetypes ? static_cast<double>(p.observations) / p.archetypes : 0.0;
            };
            for (const auto& [mode, p] :
                 {std::pair<const char*, const Pooled*>{"per-group", &single},
                  {"one-per-blade", &tracked}}) {
                const std::vector<std::string> c = p->cells();
                csv << preset << ',' << groups << ',' << groups * options.fusionFrames << ','
                    << trueBlades << ',' << mode << ',' << p->archetypes << ',' << p->errors.size()
                    << ',' << fixed(perArchetype(*p), 2) << ',' << c[0] << ',' << c[1] << ','
                    << c[2] << ',' << c[3] << ',' << fixed(tuftMs(*p), 1) << '\n';
            }
            const auto cell = [](const std::string& s) { return s.empty() ? std::string("–") : s; };
            const std::vector<std::string> a = single.cells(), b = tracked.cells();
            md << "| " << preset << " | " << groups << " (" << groups * options.fusionFrames
               << ") | " << single.archetypes << " (" << single.errors.size() << ") / "
               << tracked.archetypes << " (" << tracked.errors.size() << ") of " << trueBlades
               << " | " << cell(a[0]) << " (" << cell(a[1]) << ") / " << cell(b[0]) << " ("
               << cell(b[1]) << ") | " << cell(a[2]) << " / " << cell(b[2]) << " % | " << cell(a[3])
               << " / " << cell(b[3]) << " % | " << fixed(tuftMs(single), 1) << " / "
               << fixed(tuftMs(tracked), 1) << " |\n";
            std::cout << "  " << preset << ", " << groups << " group(s): tip RMS per group "
                      << cell(a[0]) << " mm, one per blade " << cell(b[0]) << " mm; height "
                      << cell(a[2]) << " / " << cell(b[2]) << " %; width " << cell(a[3]) << " / "
                      << cell(b[3]) << " %; archetypes " << single.archetypes << " / "
                      << tracked.archetypes << "\n";
        }
    }
    writeText(out / "modeling_groups.csv", csv.str());
    writeText(out / "modeling_groups.md", md.str());
    std::ostringstream perBlade;  // the chart: one line per preset, one archetype per blade
    {
        std::istringstream rows(csv.str());
        std::string line;
        std::getline(rows, line);
        perBlade << line << '\n';
        while (std::getline(rows, line))
            if (line.find(",one-per-blade,") != std::string::npos) perBlade << line << '\n';
    }
    writeText(out / "modeling_groups_per_blade.csv", perBlade.str());
    chart(out / "modeling_groups_per_blade.csv", out / "modeling_groups.png",
          "Tip error, one archetype per blade over its fused groups (nominal noise, 0.6-1.0 m)",
          "frames", "tip_rms_mm", "preset", "frames read (groups of 3 fused)", "tip RMS (mm)");
}

}  // namespace meadow::bench
