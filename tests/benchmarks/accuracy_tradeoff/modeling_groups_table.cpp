// 7. Modeling over fused groups: one archetype per blade, fitted to the mean of its skeletons
// over 1, 2, 4 and 8 groups of capture's fused frames (tables.h).
#include <cstdlib>
#include <glm/geometric.hpp>
#include <iostream>
#include <map>
#include <span>
#include <sstream>

#include "accuracy_tradeoff/blade_error.h"
#include "accuracy_tradeoff/tables.h"
#include "common/report.h"
#include "meadow/capture/group_segmenter.h"
#include "meadow/modeling/blade_observations.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;
using modeling::BladeFit;
using modeling::CaptureOptions;

const std::vector<int> kGroupCounts{1, 2, 4, 8};

struct TrackedFit {
    BladeFit fit;
    int trueId = 0;  // the true blade most of the track's views matched; 0: none
    int observations = 0;
};

// What capture sees of a scene's first `groups` fused groups (capture::GroupSegmenter, then
// modeling::observeGroup), and the true blade each view matches (IoU, as the other tables match).
struct Observations {
    modeling::BladeObservations seen;
    std::vector<int> trueIds;  // parallel to seen.views
};

Observations observe(const capture::Segmenter& segmenter, const Scene& scene,
                     const CaptureOptions& options, int groups) {
    Observations out;
    capture::GroupSegmenter grouper(segmenter, options.groups);
    std::vector<capture::GroupSegmentation> segmented;
    const auto keep = [&](std::vector<capture::GroupSegmentation> more) {
        for (auto& g : more) segmented.push_back(std::move(g));
    };
    const auto read = static_cast<std::size_t>(groups * options.groups.fusionFrames);
    for (std::size_t i = 0; i < read; ++i) keep(grouper.add(scene.frames[i]));
    keep(grouper.finish());
    modeling::CaptureSummary ignored;
    for (const capture::GroupSegmentation& g : segmented) {
        const std::size_t before = out.seen.views.size();
        modeling::observeGroup(g, options, out.seen, ignored);
        const BladeMatch match = matchBlades(scene.labels, g.segmentation.blades);
        for (std::size_t v = before; v < out.seen.views.size(); ++v)
            for (std::size_t b = 0; b < g.segmentation.blades.size(); ++b)
                if (g.segmentation.blades[b].id == out.seen.views[v].sighting.bladeId)
                    out.trueIds.push_back(match.foundToTrueId[b]);
    }
    return out;
}

// As modeling::captureArchetypes fits them: one archetype per track, to the mean of its
// skeletons; with tracks.enabled false, one per view (`--per-group`).
std::vector<TrackedFit> fitTracks(const Observations& seen, const CaptureOptions& options,
                                  const modeling::BladeTrackParams& tracks) {
    CaptureOptions o = options;
    o.tracks = tracks;
    modeling::CaptureSummary ignored;
    std::vector<TrackedFit> out;
    for (modeling::TrackFit& fitted : modeling::fitTracks(
             seen.seen, modeling::trackObservations(seen.seen, tracks), o, "", ignored)) {
        std::map<int, int> votes;
        for (const std::size_t i : fitted.track) ++votes[seen.trueIds[i]];
        int trueId = seen.trueIds[fitted.track.front()];
        for (const auto& [id, n] : votes)
            if (n > votes[trueId]) trueId = id;
        out.push_back({std::move(fitted.fit), trueId, static_cast<int>(fitted.track.size())});
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
              << mostGroups << " groups of " << options.groups.fusionFrames << " frames\n";
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
                                             mostGroups * options.groups.fusionFrames));
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
                csv << preset << ',' << groups << ',' << groups * options.groups.fusionFrames << ','
                    << trueBlades << ',' << mode << ',' << p->archetypes << ',' << p->errors.size()
                    << ',' << fixed(perArchetype(*p), 2) << ',' << c[0] << ',' << c[1] << ','
                    << c[2] << ',' << c[3] << ',' << fixed(tuftMs(*p), 1) << '\n';
            }
            const auto cell = [](const std::string& s) { return s.empty() ? std::string("–") : s; };
            const std::vector<std::string> a = single.cells(), b = tracked.cells();
            md << "| " << preset << " | " << groups << " (" << groups * options.groups.fusionFrames
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
