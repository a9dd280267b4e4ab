// 4. Modeling trade-off: spine error against capture time per tuft (tables.h).
#include <cmath>
#include <iostream>
#include <sstream>

#include "accuracy_tradeoff/blade_error.h"
#include "accuracy_tradeoff/tables.h"
#include "common/report.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;
using modeling::CaptureOptions;

const std::vector<int> kRefinedKnots{0, 4, 8, 16, 32, 64};  // 0: refining off (its cost)
const std::vector<int> kModelingFusionFrames{1, 3, 5};
const std::vector<float> kTolerances_mm{0.f, 0.5f, 1.f, 2.f, 4.f, 8.f};

// The charts put thread CPU time on x: on a shared, loaded machine the wall time of the same
// work varies widely between configurations (both are in the CSV).
const std::string kCpuTuftLabel =
    "CPU time per tuft: segmentation + fits (ms, one thread; wall time in the CSV)";

}  // namespace

void modelingTradeoff(const Plan& plan, const std::vector<Scene>& scenes, const fs::path& out) {
    std::cout << "modeling trade-off on " << scenes.size() << " scenes, " << plan.repetitions
              << " repetitions\n";
    struct Config {
        std::string knob, value;
        CaptureOptions options;
    };
    std::vector<Config> configs;
    for (int k : kRefinedKnots) {
        CaptureOptions o;
        o.fit.refinedKnots = k;
        configs.push_back({"refined-knots", std::to_string(k), o});
    }
    for (int f : kModelingFusionFrames) {
        CaptureOptions o;
        o.groups.fusionFrames = f;
        configs.push_back({"fusion-frames", std::to_string(f), o});
    }
    for (float tol : kTolerances_mm) {  // as `meadow capture --tolerance-mm`: widths and knots
        CaptureOptions o;
        o.fit.setTolerance_m(tol / kMillimetresPerMetre);
        configs.push_back({"tolerance-mm", fixed(tol, 1), o});
    }
    std::ostringstream csv, md;
    csv << "knob,value,time_ms,cpu_ms,spine_error_mm,spine_error_median_mm,"
           "spine_off_curve_median_mm,knot_polyline_error_mm,knot_polyline_median_mm,"
           "width_mae_pct_of_max,width_samples_mean,fitted_matched,knots_kept_mean\n";
    md << "| knob | value | capture time per tuft (ms, wall) | CPU (ms) | spine control-point "
          "error (mm, median / mean) | refined-knot polyline off truth (mm, median / mean) | "
          "width MAE (% of max) | width samples | knots kept | blades "
          "|\n|---|---|---|---|---|---|---|---|---|---|\n";
    std::vector<TradeoffRow> rows;
    for (const Config& c : configs) {
        const capture::Segmenter segmenter(c.options.segmenter);
        std::vector<double> wall, cpu;
        std::vector<float> cp, off, knots, width, samples, kept;
        for (const Scene& scene : scenes) {
            TuftCapture cap;
            const Timing t = timeMedian(plan.repetitions,
                                        [&] { cap = captureTuft(segmenter, scene, c.options); });
            wall.push_back(t.wall_ms);
            cpu.push_back(t.cpu_ms);
            const TuftScore s = scoreCapture(scene, cap);
            for (std::size_t i = 0; i < s.errors.size(); ++i) {
                cp.push_back(s.errors[i].controlPointMean_mm());
                off.push_back(s.errors[i].offCurve_mm);
                if (std::isfinite(s.errors[i].knotPolyline_mm))
                    knots.push_back(s.errors[i].knotPolyline_mm);
                width.push_back(s.errors[i].widthMaeFraction);
                samples.push_back(
                    static_cast<float>(s.matchedFits[i]->archetype.width.width_m.size()));
                kept.push_back(static_cast<float>(s.matchedFits[i]->archetype.knots_m.size()));
            }
        }
        rows.push_back(
            {c.knob, mean(cpu),
             c.knob + ',' + c.value + ',' + fixed(mean(wall), 2) + ',' + fixed(mean(cpu), 2) + ',' +
                 fixed(mean(cp), 3) + ',' + fixed(median(cp), 3) + ',' + fixed(median(off), 3) +
                 ',' + orBlank(knots, mean(knots), 3) + ',' + orBlank(knots, median(knots), 3) +
                 ',' + fixed(kPercent * mean(width), 2) + ',' + fixed(mean(samples), 1) + ',' +
                 std::to_string(cp.size()) + ',' + fixed(mean(kept), 1) + '\n'});
        md << "| " << c.knob << " | " << c.value << " | " << fixed(mean(wall), 1) << " | "
           << fixed(mean(cpu), 1) << " | " << fixed(median(cp), 2) << " / " << fixed(mean(cp), 2)
           << " | "
           << (knots.empty() ? std::string("– (refining off)")
                             : fixed(median(knots), 2) + " / " + fixed(mean(knots), 2))
           << " | " << fixed(kPercent * mean(width), 1) << " | " << fixed(mean(samples), 1) << " | "
           << fixed(mean(kept), 1) << " | " << cp.size() << " |\n";
        std::cout << "  " << c.knob << '=' << c.value << ": " << fixed(mean(wall), 1)
                  << " ms wall, " << fixed(mean(cpu), 1) << " ms CPU, spine " << fixed(mean(cp), 2)
                  << " mm, knots " << fixed(mean(knots), 2) << " mm, width "
                  << fixed(kPercent * mean(width), 1) << " %\n";
    }
    csv << sortedRows(rows);
    writeText(out / "modeling_tradeoff.csv", csv.str());
    writeText(out / "modeling_tradeoff.md", md.str());
    chart(out / "modeling_tradeoff.csv", out / "modeling_tradeoff.png",
          "Capture: fitted spine control-point error vs time per tuft (5 blade-type tufts)",
          "cpu_ms", "spine_error_median_mm", "knob", kCpuTuftLabel,
          "spine control-point error (mm, median over blades)");
    chart(out / "modeling_tradeoff.csv", out / "modeling_tradeoff_knots.png",
          "Capture: refined-knot polyline error vs time per tuft", "cpu_ms",
          "knot_polyline_median_mm", "knob", kCpuTuftLabel,
          "refined-knot polyline off the true spine (mm, median)");
    chart(out / "modeling_tradeoff.csv", out / "modeling_tradeoff_width.png",
          "Capture: width-profile error vs time per tuft", "cpu_ms", "width_mae_pct_of_max", "knob",
          kCpuTuftLabel, "width-profile MAE (% of the blade's max width)");
}

}  // namespace meadow::bench
