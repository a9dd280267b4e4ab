// 2. Capture trade-off: median IoU against segmentation time (tables.h).
#include <iostream>
#include <sstream>

#include "accuracy_tradeoff/tables.h"
#include "common/report.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;
using capture::PlaneMethod;
using capture::Segmentation;
using capture::SegmenterParams;
using modeling::CaptureOptions;

const std::vector<int> kFusionFrames{1, 2, 3, 5, 12};
// Fused by their nearest recurring readings (--fusion nearest-recurring); below 5 frames the
// share is a count of 2 and the median does as well.
const std::vector<int> kRecurringFusionFrames{5, 12};
const std::vector<float> kSmoothingSigmas_px{0.f, 1.f, 2.f, 4.f, 8.f};

}  // namespace

void captureTradeoff(const Plan& plan, const std::vector<Scene>& scenes, const fs::path& out) {
    std::cout << "capture trade-off on " << scenes.size() << " scenes, " << plan.repetitions
              << " repetitions\n";
    struct Config {
        std::string knob, value;
        SegmenterParams params;
        int fusion;
    };
    const CaptureOptions defaults{};
    std::vector<Config> configs;
    for (int f : kFusionFrames)
        configs.push_back({"fusion-frames", std::to_string(f), defaults.segmenter, f});
    for (int f : kRecurringFusionFrames) {
        SegmenterParams p = defaults.segmenter;
        p.fusion = capture::FusionMethod::NearestRecurring;
        configs.push_back({"recurring-fusion-frames", std::to_string(f), p, f});
    }
    for (float sigma : kSmoothingSigmas_px) {
        SegmenterParams p = defaults.segmenter;
        p.smoothingSigma_px = sigma;
        configs.push_back({"contour-sigma-px", fixed(sigma, 1), p, defaults.groups.fusionFrames});
    }
    for (PlaneMethod m :
         {PlaneMethod::None, PlaneMethod::Ransac, PlaneMethod::OrganizedMultiPlane}) {
        SegmenterParams p = defaults.segmenter;
        p.planeMethod = m;
        configs.push_back({"plane-fit", capture::toString(m), p, defaults.groups.fusionFrames});
    }
    std::ostringstream csv, md;
    csv << "knob,value,time_ms,cpu_ms,median_iou,recall,precision\n";
    md << "| knob | value | time per segmentation (ms, wall) | CPU (ms) | median IoU | recall | "
          "precision |\n|---|---|---|---|---|---|---|\n";
    std::vector<TradeoffRow> rows;
    for (const Config& c : configs) {
        const capture::Segmenter segmenter(c.params);
        std::vector<double> iou, wall, cpu;
        int truth = 0, found = 0, matched = 0;
        for (const Scene& scene : scenes) {
            Segmentation seg;
            const Timing t = timeMedian(plan.repetitions,
                                        [&] { seg = segmentScene(segmenter, scene, c.fusion); });
            wall.push_back(t.wall_ms);
            cpu.push_back(t.cpu_ms);
            const BladeMatch m = matchBlades(scene.labels, seg.blades);
            iou.insert(iou.end(), m.trueBestIou.begin(), m.trueBestIou.end());
            truth += static_cast<int>(m.trueIds.size());
            found += static_cast<int>(seg.blades.size());
            matched += m.matched;
        }
        const double recall = truth ? static_cast<double>(matched) / truth : 1.0;
        const double precision = found ? static_cast<double>(matched) / found : 1.0;
        rows.push_back({c.knob, mean(cpu),
                        c.knob + ',' + c.value + ',' + fixed(mean(wall), 2) + ',' +
                            fixed(mean(cpu), 2) + ',' + fixed(median(iou), 4) + ',' +
                            fixed(recall, 3) + ',' + fixed(precision, 3) + '\n'});
        md << "| " << c.knob << " | " << c.value << " | " << fixed(mean(wall), 1) << " | "
           << fixed(mean(cpu), 1) << " | " << fixed(median(iou), 3) << " | " << fixed(recall, 2)
           << " | " << fixed(precision, 2) << " |\n";
        std::cout << "  " << c.knob << '=' << c.value << ": " << fixed(mean(wall), 1)
                  << " ms wall, " << fixed(mean(cpu), 1) << " ms CPU, median IoU "
                  << fixed(median(iou), 3) << '\n';
    }
    csv << sortedRows(rows);
    writeText(out / "capture_tradeoff.csv", csv.str());
    writeText(out / "capture_tradeoff.md", md.str());
    chart(out / "capture_tradeoff.csv", out / "capture_tradeoff.png",
          "Segmentation: median blade IoU vs time (blade-type presets, nominal noise)", "cpu_ms",
          "median_iou", "knob", "CPU time per segmentation (ms, one thread; wall time in the CSV)",
          "median blade IoU (pixels, vs truth)");
}

}  // namespace meadow::bench
