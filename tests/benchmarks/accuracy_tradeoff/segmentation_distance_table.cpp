// 6. Segmentation over camera distance: blade-type preset x distance at nominal noise (tables.h).
#include <iostream>
#include <sstream>

#include "accuracy_tradeoff/tables.h"
#include "common/report.h"

namespace meadow::bench {

void segmentationOverDistance(const Plan& plan, const std::filesystem::path& out) {
    std::cout << "segmentation over distance: " << plan.bladeTypes.size() << " presets x "
              << plan.segmentationDistances_m.size() << " distances x " << plan.segmentationSeeds
              << " seeds, nominal noise, one frame\n";
    std::ostringstream csv, md;
    csv << "preset,distance_m,seeds,true_blades,found_blades,recall,precision,median_iou,"
           "empty_frames\n";
    md << "| preset | distance (m) | true / found (per frame) | recall | precision | median IoU | "
          "frames without blades |\n|---|---|---|---|---|---|---|\n";
    const capture::Segmenter segmenter;
    for (const std::string& preset : plan.bladeTypes)
        for (float distance_m : plan.segmentationDistances_m) {
            SegmentationTally t;
            for (int seed = 1; seed <= plan.segmentationSeeds; ++seed) {
                const Scene scene = renderScene(preset, kNominalNoise,
                                                static_cast<std::uint64_t>(seed), distance_m, 1);
                const capture::Segmentation seg = segmenter.segment(scene.frames.front());
                t.add(matchBlades(scene.labels, seg.blades), seg);
            }
            const double seeds = plan.segmentationSeeds;
            csv << preset << ',' << fixed(distance_m, 2) << ',' << plan.segmentationSeeds << ','
                << fixed(t.trueBlades / seeds, 2) << ',' << fixed(t.foundBlades / seeds, 2) << ','
                << fixed(mean(t.recall), 3) << ','
                << (t.precision.empty() ? std::string() : fixed(mean(t.precision), 3)) << ','
                << fixed(mean(t.medianIou), 3) << ',' << t.emptyFrames << '\n';
            md << "| " << preset << " | " << fixed(distance_m, 1) << " | "
               << fixed(t.trueBlades / seeds, 1) << " / " << fixed(t.foundBlades / seeds, 1)
               << " | " << fixed(mean(t.recall), 2) << " | "
               << (t.precision.empty() ? std::string("–") : fixed(mean(t.precision), 2)) << " | "
               << fixed(mean(t.medianIou), 2) << " | " << t.emptyFrames << " |\n";
            std::cout << "  " << preset << " at " << fixed(distance_m, 1) << " m: recall "
                      << fixed(mean(t.recall), 2) << ", median IoU " << fixed(mean(t.medianIou), 2)
                      << '\n';
        }
    writeText(out / "segmentation_distance.csv", csv.str());
    writeText(out / "segmentation_distance.md", md.str());
    chart(out / "segmentation_distance.csv", out / "segmentation_distance.png",
          "Segmentation: blade recall vs camera distance (nominal noise, one frame)", "distance_m",
          "recall", "preset", "camera distance to the tuft (m)",
          "blade recall (pixel IoU >= 0.5 with a true blade)");
}

}  // namespace meadow::bench
