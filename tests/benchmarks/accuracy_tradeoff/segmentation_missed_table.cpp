// 9. What the sensor leaves of the blades segmentation misses, and the recall bound that follows
// (tables.h).
#include <iostream>
#include <sstream>

#include "accuracy_tradeoff/tables.h"
#include "common/report.h"
#include "meadow/synth/blade_match.h"

namespace meadow::bench {
namespace {

// A missed blade read on under this share of its pixels is read in pieces a cut cannot join.
constexpr double kLittleRead = 0.5;
// A missed blade with a depth step on under this share of its contact lies flush on a neighbour.
constexpr double kFlushContact = 0.3;

}  // namespace

void segmentationMissed(const Plan& plan, const std::filesystem::path& out) {
    std::cout << "what the sensor leaves of missed blades: " << plan.bladeTypes.size()
              << " presets x " << plan.missedFrames.size() << " frame counts x " << plan.fusionSeeds
              << " seeds, nominal noise\n";
    std::ostringstream csv, md;
    csv << "preset,frames,seeds,true_blades,missed,read_under_half,flush,neither,recall,"
           "recall_bound,read_share_median,read_pieces_median,step_median_mm\n";
    md << "| preset | frames | missed / true | read on under half | flush on a neighbour | "
          "neither | recall | recall bound | read share (median) | pieces read (median) | depth "
          "step (median, mm) |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string& preset : plan.bladeTypes)
        for (const int frames : plan.missedFrames) {
            capture::SegmenterParams params;
            if (frames > 1) params.fusion = capture::FusionMethod::NearestRecurring;
            const capture::Segmenter segmenter(params);
            int truth = 0, matched = 0, underHalf = 0, flush = 0, neither = 0;
            std::vector<double> share, pieces, step;
            for (int seed = 1; seed <= plan.fusionSeeds; ++seed) {
                const Scene scene = renderScene(preset, kNominalNoise,
                                                static_cast<std::uint64_t>(seed), 0.f, frames);
                const capture::Segmentation seg = segmentScene(segmenter, scene, frames);
                const synth::BladeMatch m = synth::matchBlades(scene.labels, seg.blades);
                truth += static_cast<int>(m.trueIds.size());
                matched += m.matched;
                for (std::size_t t = 0; t < m.trueIds.size(); ++t) {
                    if (m.trueBestIou[t] >= synth::kMatchIou) continue;
                    // What the sensor read of it: frame 0's readings (a fused view reads more).
                    const synth::MissedBlade missed = synth::describeMissed(
                        scene.labels, scene.exact_m, scene.frames.front().depth_mm, m.trueIds[t]);
                    share.push_back(missed.readShare);
                    pieces.push_back(missed.readPieces);
                    if (missed.contact_px > 0) step.push_back(missed.medianStep_mm);
                    const bool little = missed.readShare < kLittleRead;
                    const bool flat = missed.contact_px > 0 && missed.steppedShare < kFlushContact;
                    underHalf += little;
                    flush += flat;
                    neither += !little && !flat;
                }
            }
            const int missedCount = truth - matched;
            // No cut of the depth image finds a blade it barely reads or that lies flush on a
            // neighbour: the rest could be found at best.
            const double recall = truth ? static_cast<double>(matched) / truth : 0.0;
            const double bound = truth ? static_cast<double>(matched + neither) / truth : 0.0;
            csv << preset << ',' << frames << ',' << plan.fusionSeeds << ',' << truth << ','
                << missedCount << ',' << underHalf << ',' << flush << ',' << neither << ','
                << fixed(recall, 3) << ',' << fixed(bound, 3) << ',' << fixed(median(share), 3)
                << ',' << fixed(median(pieces), 1) << ',' << fixed(median(step), 2) << '\n';
            md << "| " << preset << " | " << frames << " | " << missedCount << " / " << truth
               << " | " << underHalf << " | " << flush << " | " << neither << " | "
               << fixed(recall, 2) << " | " << fixed(bound, 2) << " | " << fixed(median(share), 2)
               << " | " << fixed(median(pieces), 1) << " | " << fixed(median(step), 2) << " |\n";
            std::cout << "  " << preset << ", " << frames << " frame(s): recall "
                      << fixed(recall, 2) << ", bound " << fixed(bound, 2) << '\n';
        }
    md << "\nA missed blade is a true blade no found blade matches at pixel IoU >= 0.5 (seeds 1-"
       << plan.fusionSeeds
       << "; several frames are fused by their nearest recurring readings). Read on under half: "
          "under half its pixels read within 10 mm of its surface in frame 0. Flush: touching "
          "other blades with a depth step of 5 mm or more on under 30 % of the contact. The "
          "recall bound counts the blades matched plus the missed ones that are neither: what a "
          "partition that cuts the depth image could reach at best.\n";
    writeText(out / "segmentation_missed.csv", csv.str());
    writeText(out / "segmentation_missed.md", md.str());
}

}  // namespace meadow::bench
