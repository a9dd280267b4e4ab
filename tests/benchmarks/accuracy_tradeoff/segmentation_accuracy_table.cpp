// 1. Segmentation accuracy: preset x noise (tables.h).
#include <iostream>
#include <map>
#include <sstream>

#include "accuracy_tradeoff/tables.h"
#include "common/report.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;
using capture::BladeContour;
using capture::BladeFlag;
using capture::Segmentation;

const std::vector<BladeFlag> kAllFlags{BladeFlag::Overlapping, BladeFlag::CurlsSideways,
                                       BladeFlag::TooThin,     BladeFlag::BaseHidden,
                                       BladeFlag::Asymmetric,  BladeFlag::Truncated};

}  // namespace

void segmentationAccuracy(const Plan& plan, const fs::path& out) {
    std::cout << "segmentation accuracy: " << plan.segmentationPresets.size() << " presets x "
              << plan.noises.size() << " noise scales x " << plan.segmentationSeeds << " seeds\n";
    std::ostringstream csv, md;
    csv << "preset,noise_scale,seeds,true_blades,found_blades,recall,precision,median_iou,"
           "flagged_blades,unflagged_unmatched";
    for (BladeFlag f : kAllFlags) csv << ",flag_" << capture::toString(f);
    csv << ",cluster_flags,empty_frames,zero_recall_frames\n";
    md << "| preset | noise | true / found (per frame) | recall | precision | median IoU | "
          "frames with no blade matched | flags raised (blades, "
       << plan.segmentationSeeds
       << " frames) | unmatched and unflagged |\n|---|---|---|---|---|---|---|---|---|\n";
    const capture::Segmenter segmenter;
    for (const std::string& preset : plan.segmentationPresets)
        for (float noise : plan.noises) {
            SegmentationTally t;
            int flagged = 0, silentWrong = 0, clusterFlags = 0, zeroRecall = 0;
            std::map<std::string, int> flagKinds;
            std::map<BladeFlag, int> perFlag;
            for (int seed = 1; seed <= plan.segmentationSeeds; ++seed) {
                const Scene scene =
                    renderScene(preset, noise, static_cast<std::uint64_t>(seed), 0.f, 1);
                const Segmentation seg = segmenter.segment(scene.frames.front());
                const BladeMatch m = matchBlades(scene.labels, seg.blades);
                t.add(m, seg);
                if (m.matched == 0 && !m.trueIds.empty()) ++zeroRecall;
                for (std::size_t b = 0; b < seg.blades.size(); ++b) {
                    const BladeContour& blade = seg.blades[b];
                    if (!blade.flags.empty()) ++flagged;
                    if (blade.flags.empty() && m.foundToTrueId[b] == 0) ++silentWrong;
                    for (BladeFlag f : blade.flags) {
                        ++perFlag[f];
                        ++flagKinds[capture::toString(f)];
                    }
                }
                for (const auto& c : seg.clusters) {
                    clusterFlags += static_cast<int>(c.flags.size());
                    for (BladeFlag f : c.flags) ++flagKinds["cluster " + capture::toString(f)];
                }
            }
            const double seeds = plan.segmentationSeeds;
            csv << preset << ',' << noise << ',' << plan.segmentationSeeds << ','
                << fixed(t.trueBlades / seeds, 2) << ',' << fixed(t.foundBlades / seeds, 2) << ','
                << fixed(mean(t.recall), 3) << ','
                << (t.precision.empty() ? std::string() : fixed(mean(t.precision), 3)) << ','
                << fixed(mean(t.medianIou), 3) << ',' << flagged << ',' << silentWrong;
            for (BladeFlag f : kAllFlags) csv << ',' << perFlag[f];
            csv << ',' << clusterFlags << ',' << t.emptyFrames << ',' << zeroRecall << '\n';
            md << "| " << preset << " | " << noiseName(noise) << " | "
               << fixed(t.trueBlades / seeds, 1) << " / " << fixed(t.foundBlades / seeds, 1)
               << " | " << fixed(mean(t.recall), 2) << " | "
               << (t.precision.empty() ? std::string("–") : fixed(mean(t.precision), 2)) << " | "
               << fixed(mean(t.medianIou), 2) << " | " << zeroRecall << " | "
               << flagCounts(flagKinds, t.emptyFrames) << " | " << silentWrong << " |\n";
            std::cout << "  " << preset << ' ' << noiseName(noise) << ": recall "
                      << fixed(mean(t.recall), 2) << ", median IoU " << fixed(mean(t.medianIou), 2)
                      << '\n';
        }
    writeText(out / "segmentation_accuracy.csv", csv.str());
    writeText(out / "segmentation_accuracy.md", md.str());
}

}  // namespace meadow::bench
