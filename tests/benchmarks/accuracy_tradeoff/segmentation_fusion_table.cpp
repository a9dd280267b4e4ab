// 8. Segmentation over fused frames of a still tuft, by median and by nearest recurring reading,
// scored three ways (tables.h).
#include <iostream>
#include <sstream>

#include "accuracy_tradeoff/tables.h"
#include "common/report.h"
#include "meadow/synth/blade_match.h"

namespace meadow::bench {
namespace {

// One way of fusing: its name and how many frames.
struct Fusion {
    capture::FusionMethod method;
    int frames;
    [[nodiscard]] std::string name() const {
        return frames == 1 ? "none" : capture::toString(method);
    }
};

std::vector<Fusion> fusions(const Plan& plan) {
    std::vector<Fusion> out;
    for (const auto method :
         {capture::FusionMethod::Median, capture::FusionMethod::NearestRecurring})
        for (const int frames : plan.fusionFrames)
            if (frames > 1 || method == capture::FusionMethod::Median)
                out.push_back({method, frames});
    return out;
}

// Recall and median IoU pooled over tufts, one list of per-true-blade IoUs each way.
struct Pooled {
    std::vector<double> strict, tolerant, perfect;
    [[nodiscard]] static double recall(const std::vector<double>& iou) {
        int n = 0;
        for (const double x : iou) n += x >= synth::kMatchIou;
        return iou.empty() ? 0.0 : static_cast<double>(n) / static_cast<double>(iou.size());
    }
};

}  // namespace

void segmentationOverFusion(const Plan& plan, const std::filesystem::path& out) {
    const std::vector<Fusion> ways = fusions(plan);
    const int mostFrames = ways.back().frames;
    std::cout << "segmentation over fused frames: " << plan.bladeTypes.size() << " presets x "
              << ways.size() << " fusions x " << plan.fusionSeeds << " seeds, nominal noise\n";
    std::ostringstream csv, md;
    csv << "preset,fusion,frames,seeds,true_blades,recall,median_iou,perfect_partition_recall,"
           "perfect_partition_median_iou,tolerant_recall,tolerant_median_iou\n";
    md << "| preset | fusion | frames | recall | median IoU | with a perfect partition: recall / "
          "median IoU | with a pixel's tolerance: recall / median IoU |\n"
          "|---|---|---|---|---|---|---|\n";
    for (const std::string& preset : plan.bladeTypes) {
        std::vector<Scene> scenes;
        for (int seed = 1; seed <= plan.fusionSeeds; ++seed)
            scenes.push_back(renderScene(preset, kNominalNoise, static_cast<std::uint64_t>(seed),
                                         0.f, mostFrames));
        for (const Fusion& way : ways) {
            capture::SegmenterParams params;
            params.fusion = way.method;
            const capture::Segmenter segmenter(params);
            Pooled p;
            for (const Scene& scene : scenes) {
                const capture::Segmentation seg = segmentScene(segmenter, scene, way.frames);
                const synth::BladeMatch strict = synth::matchBlades(scene.labels, seg.blades);
                const synth::BladeMatch tolerant =
                    synth::matchBlades(scene.labels, seg.blades, /*tolerant=*/true);
                const std::vector<double> perfect =
                    synth::perfectPartitionIou(scene.labels, seg.blades, strict);
                p.strict.insert(p.strict.end(), strict.trueBestIou.begin(),
                                strict.trueBestIou.end());
                p.tolerant.insert(p.tolerant.end(), tolerant.trueBestIou.begin(),
                                  tolerant.trueBestIou.end());
                p.perfect.insert(p.perfect.end(), perfect.begin(), perfect.end());
            }
            csv << preset << ',' << way.name() << ',' << way.frames << ',' << plan.fusionSeeds
                << ',' << p.strict.size() << ',' << fixed(Pooled::recall(p.strict), 3) << ','
                << fixed(median(p.strict), 3) << ',' << fixed(Pooled::recall(p.perfect), 3) << ','
                << fixed(median(p.perfect), 3) << ',' << fixed(Pooled::recall(p.tolerant), 3) << ','
                << fixed(median(p.tolerant), 3) << '\n';
            md << "| " << preset << " | " << way.name() << " | " << way.frames << " | "
               << fixed(Pooled::recall(p.strict), 2) << " | " << fixed(median(p.strict), 2) << " | "
               << fixed(Pooled::recall(p.perfect), 2) << " / " << fixed(median(p.perfect), 2)
               << " | " << fixed(Pooled::recall(p.tolerant), 2) << " / "
               << fixed(median(p.tolerant), 2) << " |\n";
            std::cout << "  " << preset << ", " << way.name() << " x" << way.frames << ": recall "
                      << fixed(Pooled::recall(p.strict), 2) << ", perfect partition "
                      << fixed(Pooled::recall(p.perfect), 2) << '\n';
        }
    }
    md << "\nRecall: true blades matched one to one by a found blade at pixel IoU >= 0.5, over "
       << plan.fusionSeeds
       << " seeds. A perfect partition gives each true blade every found pixel on it: where its "
          "recall is 1, the mask holds every blade and the partition loses them. A pixel's "
          "tolerance counts a found pixel within one pixel of a true blade as on it.\n";
    writeText(out / "segmentation_fusion.csv", csv.str());
    writeText(out / "segmentation_fusion.md", md.str());
}

}  // namespace meadow::bench
