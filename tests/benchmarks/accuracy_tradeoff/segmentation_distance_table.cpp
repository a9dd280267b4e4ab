// 6. Segmentation over camera distance: blade-type preset x distance at nominal noise (tables.h).
#include <iostream>
#include <sstream>

#include "accuracy_tradeoff/report.h"
#include "accuracy_tradeoff/tables.h"

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
            std::vector<double> recall, precision, medianIou;
            double trueSum = 0.0, foundSum = 0.0;
            int empty = 0;
            for (int seed = 1; seed <= plan.segmentationSeeds; ++seed) {
                const Scene scene = renderScene(preset, kNominalNoise,
                                                static_cast<std::uint64_t>(seed), distance_m, 1);
                const capture::Segmentation seg = segmenter.segment(scene.frames.front());
                const BladeMatch m = matchBlades(scene.labels, seg.blades);
                const auto nTrue = static_cast<double>(m.trueIds.size());
                const auto nFound = static_cast<double>(seg.blades.size());
                trueSum += nTrue;
                foundSum += nFound;
                recall.push_back(nTrue > 0 ? m.matched / nTrue : 1.0);
                if (nFound > 0) precision.push_back(m.matched / nFound);  // else undefined
                medianIou.push_back(median(m.trueBestIou));
                empty += seg.empty();
            }
            const double seeds = plan.segmentationSeeds;
            csv << preset << ',' << fixed(distance_m, 2) << ',' << plan.segmentationSeeds << ','
                << fixed(trueSum / seeds, 2) << ',' << fixed(foundSum / seeds, 2) << ','
                << fixed(mean(recall), 3) << ','
                << (precision.empty() ? std::string() : fixed(mean(precision), 3)) << ','
                << fixed(mean(medianIou), 3) << ',' << empty << '\n';
            md << "| " << preset << " | " << fixed(distance_m, 1) << " | "
               << fixed(trueSum / seeds, 1) << " / " << fixed(foundSum / seeds, 1) << " | "
               << fixed(mean(recall), 2) << " | "
               << (precision.empty() ? std::string("–") : fixed(mean(precision), 2)) << " | "
               << fixed(mean(medianIou), 2) << " | " << empty << " |\n";
            std::cout << "  " << preset << " at " << fixed(distance_m, 1) << " m: recall "
                      << fixed(mean(recall), 2) << ", median IoU " << fixed(mean(medianIou), 2)
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
