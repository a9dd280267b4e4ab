// 11-12. Blades tracked over 12 frames of a still tuft: capture's groups against one segmentation
// of all 12 frames, and how far the sensor's readings reach toward each true tip (tables.h).
#include <glm/geometric.hpp>
#include <iostream>
#include <sstream>

#include "accuracy_tradeoff/tables.h"
#include "common/report.h"
#include "support/tracked_tips.h"

namespace meadow::bench {
namespace {

using test::addTipErrors;
using test::kTrackedFrames;
using test::kTrackedFusedFrames;
using test::observeTuft;
using test::TipErrors;
using test::TrackedTuft;

const std::vector<std::string> kLeafPresets{"quadratic-leaf", "shrub-leaf", "bamboo-leaf",
                                            "sharp-tip"};

// A reading within this of the true surface is a reading of it.
constexpr float kOnSurface_m = 0.010f;
// Walking the true spine back from its tip in steps of this length.
constexpr float kReachStep_m = 0.00025f;
// What recurs: read in at least this many of the 12 frames (recurring_readings.h's share).
constexpr int kRecurringFrames = 5;

// How many frames read the true surface point p in its pixel's 3 x 3 neighbourhood.
int framesReading(const synth::RenderedTuft& t, const glm::vec3& p) {
    const capture::Intrinsics& k = t.frames.front().intrinsics;
    const glm::vec2 px = k.project(p);
    const int u = static_cast<int>(std::lround(px.x)), v = static_cast<int>(std::lround(px.y));
    int n = 0;
    for (const auto& f : t.frames) {
        bool read = false;
        for (int dv = -1; dv <= 1 && !read; ++dv)
            for (int du = -1; du <= 1 && !read; ++du) {
                const cv::Point q(u + du, v + dv);
                if (!cv::Rect({}, f.depth_mm.size()).contains(q)) continue;
                const std::uint16_t d = f.depth_mm(q);
                read = d > 0 && std::abs(d / 1000.f - p.z) <= kOnSurface_m;
            }
        n += read;
    }
    return n;
}

double maxOf(const std::vector<double>& v) {
    return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

}  // namespace

void tracksOverFusion(const Plan& plan, const std::filesystem::path& out) {
    std::cout << "tracked tips, 4 groups of 3 against 1 group of 12: " << plan.bladeTypes.size()
              << " presets x " << plan.distances_m.size() << " distances x " << plan.trackSeeds
              << " seeds\n";
    capture::SegmenterParams recurringFusion;
    recurringFusion.fusion = capture::FusionMethod::NearestRecurring;
    std::ostringstream csv, md;
    csv << "preset,mode,seeds,true_blades,tracked_blades,tip_rms_mm\n";
    md << "| preset | 4 groups of 3 by median: blades fitted, tip RMS (mm) | 1 group of 12 by "
          "nearest recurring reading |\n|---|---|---|\n";
    for (const std::string& preset : plan.bladeTypes) {
        TipErrors groups, one;
        for (int seed = 1; seed <= plan.trackSeeds; ++seed)
            for (const float distance_m : plan.distances_m) {
                const auto s = static_cast<std::uint64_t>(seed);
                addTipErrors(observeTuft(preset, distance_m, true, s), kTrackedFusedFrames, groups);
                addTipErrors(
                    observeTuft(preset, distance_m, true, s, recurringFusion, kTrackedFrames),
                    kTrackedFrames, one);
            }
        for (const auto& [mode, e] :
             {std::pair<const char*, const TipErrors*>{"groups", &groups}, {"one-of-12", &one}})
            csv << preset << ',' << mode << ',' << plan.trackSeeds << ',' << e->trueBlades << ','
                << e->tracked << ',' << fixed(e->trackedRms_mm(), 2) << '\n';
        md << "| " << preset << " | " << groups.tracked << " of " << groups.trueBlades << ", "
           << fixed(groups.trackedRms_mm(), 2) << " | " << one.tracked << " of " << one.trueBlades
           << ", " << fixed(one.trackedRms_mm(), 2) << " |\n";
        std::cout << "  " << preset << ": " << fixed(groups.trackedRms_mm(), 2) << " / "
                  << fixed(one.trackedRms_mm(), 2) << " mm\n";
    }
    md << "\nBoth with the tip trails' readings recurring over the 12 frames; each track fitted to "
          "the mean of its views, as `meadow capture` fits it (the first is capture's default, "
          "the second `--fuse 12 --fusion nearest-recurring`).\n";
    writeText(out / "tracks_fusion.csv", csv.str());
    writeText(out / "tracks_fusion.md", md.str());
}

void tipReach(const Plan& plan, const std::filesystem::path& out) {
    std::cout << "tip reach: " << kLeafPresets.size() << " presets x " << plan.distances_m.size()
              << " distances x " << plan.trackSeeds << " seeds\n";
    modeling::BladeFitParams unextended;
    unextended.tip.enabled = false;
    std::ostringstream csv, md;
    csv << "preset,seeds,blades,unseen_one_frame_mean_mm,unseen_one_frame_max_mm,"
           "unseen_recurring_mean_mm,unseen_recurring_max_mm,tips,short_mean_mm,spread_sd_mm,"
           "across_rms_mm,rms_with_distance_mean_added_mm\n";
    md << "| preset | blades | beyond what 1 frame reads: mean, max (mm) | beyond what 5 of 12 "
          "read: mean, max (mm) | unextended tips: short along the tangent, mean (mm) | spread "
          "about each distance's mean (SD, mm) | across (RMS, mm) | RMS were each distance's mean "
          "added (mm) |\n|---|---|---|---|---|---|---|---|\n";
    for (const std::string& preset : kLeafPresets) {
        std::vector<double> unseenAll, unseenRecurring, allAlong;
        double spreadSq = 0.0, acrossSq = 0.0;
        for (const float distance_m : plan.distances_m) {
            std::vector<double> along;
            for (int seed = 1; seed <= plan.trackSeeds; ++seed) {
                const TrackedTuft o =
                    observeTuft(preset, distance_m, true, static_cast<std::uint64_t>(seed), {},
                                kTrackedFusedFrames, unextended);
                // How far toward each true tip the readings reach.
                for (const synth::SyntheticBlade& blade : o.tuft.tuft.blades) {
                    const modeling::QuadraticBezier spine = blade.spineInCamera_m();
                    const float length_m = spine.length();
                    float reachAll = -1.f, reachRecurring = -1.f;
                    for (float back = 0.f; back < length_m && reachRecurring < 0.f;
                         back += kReachStep_m) {
                        const float fraction = 1.f - back / length_m;
                        const int n = framesReading(
                            o.tuft, spine.at(spine.parameterAtLengthFraction(fraction)));
                        if (n >= 1 && reachAll < 0.f) reachAll = back;
                        if (n >= kRecurringFrames) reachRecurring = back;
                    }
                    unseenAll.push_back(1e3 * std::max(reachAll, 0.f));
                    unseenRecurring.push_back(1e3 * std::max(reachRecurring, 0.f));
                }
                // Where a tracked tip lands without any extension, against the true tip.
                for (const auto& track : modeling::trackBlades(o.seen.skeletons)) {
                    const int id = o.trueBladeOfTrack(track);
                    if (id == 0) continue;
                    const modeling::QuadraticBezier fitted =
                        modeling::fitArchetype(modeling::trackSkeleton(o.seen.skeletons, track),
                                               unextended)
                            .spineCamera_m;
                    const glm::vec3 miss = o.tuft.tuft.blades.at(static_cast<std::size_t>(id - 1))
                                               .spineInCamera_m()
                                               .v2 -
                                           fitted.v2;
                    const glm::vec3 tangent = glm::normalize(fitted.tangent(1.f));
                    const glm::vec3 across = miss - glm::dot(miss, tangent) * tangent;
                    along.push_back(1e3 * glm::dot(miss, tangent));
                    acrossSq += 1e6 * glm::dot(across, across);
                }
            }
            const double m = mean(along);
            for (const double a : along) spreadSq += (a - m) * (a - m);
            allAlong.insert(allAlong.end(), along.begin(), along.end());
        }
        const auto tips = static_cast<double>(std::max<std::size_t>(allAlong.size(), 1));
        csv << preset << ',' << plan.trackSeeds << ',' << unseenAll.size() << ','
            << fixed(mean(unseenAll), 2) << ',' << fixed(maxOf(unseenAll), 2) << ','
            << fixed(mean(unseenRecurring), 2) << ',' << fixed(maxOf(unseenRecurring), 2) << ','
            << allAlong.size() << ',' << fixed(mean(allAlong), 2) << ','
            << fixed(std::sqrt(spreadSq / tips), 2) << ',' << fixed(std::sqrt(acrossSq / tips), 2)
            << ',' << fixed(std::sqrt((spreadSq + acrossSq) / tips), 2) << '\n';
        md << "| " << preset << " | " << unseenAll.size() << " | " << fixed(mean(unseenAll), 2)
           << ", " << fixed(maxOf(unseenAll), 2) << " | " << fixed(mean(unseenRecurring), 2) << ", "
           << fixed(maxOf(unseenRecurring), 2) << " | " << fixed(mean(allAlong), 2) << " | "
           << fixed(std::sqrt(spreadSq / tips), 2) << " | " << fixed(std::sqrt(acrossSq / tips), 2)
           << " | " << fixed(std::sqrt((spreadSq + acrossSq) / tips), 2) << " |\n";
        std::cout << "  " << preset << ": unseen past what recurs "
                  << fixed(mean(unseenRecurring), 2) << " mm on average\n";
    }
    md << "\nWalking each true spine back from its tip: the first point read within 10 mm of its "
          "depth in its pixel's 3 x 3 neighbourhood, in at least 1 and in at least 5 of the 12 "
          "frames (what recurs). Beyond it the tip is unseen and can only be extrapolated. The "
          "last four columns fit each track without extending its tip: if each distance's mean "
          "shortfall were known and added, what would be left is the spread about it and the "
          "error across the tangent.\n";
    writeText(out / "tip_reach.csv", csv.str());
    writeText(out / "tip_reach.md", md.str());
}

}  // namespace meadow::bench
