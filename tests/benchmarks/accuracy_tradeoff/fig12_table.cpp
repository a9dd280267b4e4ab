// 5. Fan & Sheng 2017 Fig. 12 on the captured skeletons (tables.h).
#include <algorithm>
#include <iostream>
#include <sstream>
#include <utility>

#include "accuracy_tradeoff/tables.h"
#include "common/report.h"
#include "meadow/modeling/chain_simulation.h"
#include "meadow/synth/refiner_comparison.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;
using modeling::BladeFit;

const std::vector<int> kFig12Knots{128, 64, 32, 16, 8};  // 128 = the full skeleton, error 0
constexpr int kFig12RandomTrials = 4;
constexpr int kMaxFig12BladesPerPreset = 8;  // each costs seconds of Hausdorff

// Refiner names as chart series: gnuplot would read '_' as a subscript in the key.
std::string seriesName(modeling::RefinerKind kind) {
    std::string name = modeling::toString(kind);
    std::replace(name.begin(), name.end(), '_', '-');
    return name;
}

}  // namespace

void appendFig12Skeleton(Fig12Input& input, const std::string& preset, const BladeFit& fit) {
    auto& blades = input.restKnots[preset];
    if (static_cast<int>(blades.size()) >= kMaxFig12BladesPerPreset) return;
    std::vector<glm::vec3> local;
    for (const glm::vec3& p : fit.skeleton.points_m) local.push_back(fit.frame.toLocal(p));
    if (local.size() >= 3) blades.push_back(std::move(local));
}

void fig12(const Fig12Input& input, const fs::path& out) {
    std::cout << "Fig. 12 (refiners)\n";
    using modeling::RefinerKind;
    modeling::ChainSimulationParams sim;  // as blade_fit.cpp: blade-local +Y up, gravity -Y
    sim.up = {0.f, 1.f, 0.f};
    sim.gravity_mps2 = {0.f, -9.81f, 0.f};
    // Pooled over presets: compareRefiners averages uniformly over blades, so the blade-weighted
    // mean of the per-preset rows is the pooled row (without running every blade twice).
    std::map<std::pair<int, RefinerKind>, synth::RefinerComparisonRow> pooled;
    std::size_t pooledBlades = 0;
    std::ostringstream md;
    md << "| preset | blades | knots | movement similarity | random | mean | geometry only |\n"
          "|---|---|---|---|---|---|---|\n";
    const auto mdRows = [&](const std::string& label, std::size_t blades,
                            const std::vector<synth::RefinerComparisonRow>& rows,
                            float synth::RefinerComparisonRow::*metric) {
        for (int k : kFig12Knots) {
            if (k == kFig12Knots.front()) continue;  // nothing culled: 0 for every refiner
            std::map<RefinerKind, float> at;
            for (const auto& r : rows)
                if (r.knots == k) at[r.refiner] = r.*metric;
            md << "| " << label << " | " << blades << " | " << k << " | "
               << fixed(at[RefinerKind::MovementSimilarity], 2) << " | "
               << fixed(at[RefinerKind::Random], 2) << " | " << fixed(at[RefinerKind::Mean], 2)
               << " | " << fixed(at[RefinerKind::GeometryOnly], 2) << " |\n";
        }
    };
    std::uint64_t seed = 1;
    for (const auto& [preset, rest] : input.restKnots) {
        if (rest.empty()) continue;
        std::vector<modeling::KnotTrajectories> frames;
        for (const auto& knots : rest) {
            sim.seed = seed++;
            frames.push_back(modeling::simulateChain(knots, sim));
        }
        const auto rows = synth::compareRefiners(rest, frames, kFig12Knots, {}, kFig12RandomTrials);
        const fs::path csv = out / ("fig12_" + preset + ".csv");
        synth::writeRefinerComparisonCsv(csv, rows);
        std::cout << "  wrote " << csv.string() << " (" << rest.size() << " blades)\n";
        mdRows(preset, rest.size(), rows, &synth::RefinerComparisonRow::refinedHausdorff_mm);
        for (const auto& r : rows) {
            auto& p = pooled[{r.knots, r.refiner}];
            p.knots = r.knots;
            p.refiner = r.refiner;
            const auto w = static_cast<float>(rest.size());
            p.refinedHausdorff_mm += w * r.refinedHausdorff_mm;
            p.hausdorff_mm += w * r.hausdorff_mm;
            p.maxDeviation_mm += w * r.maxDeviation_mm;
        }
        pooledBlades += rest.size();
    }
    if (pooledBlades == 0) {
        std::cerr << "  no fitted skeletons: Fig. 12 skipped\n";
        return;
    }
    std::vector<synth::RefinerComparisonRow> rows;
    for (auto& [key, r] : pooled) {
        const auto w = static_cast<float>(pooledBlades);
        r.refinedHausdorff_mm /= w;
        r.hausdorff_mm /= w;
        r.maxDeviation_mm /= w;
        rows.push_back(r);
    }
    // Per refiner, knots ascending: the order chart.sh joins the points in.
    std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) {
        return a.refiner != b.refiner ? a.refiner < b.refiner : a.knots < b.knots;
    });
    std::ostringstream csv;
    csv << "knots,refiner,refined_hausdorff_mm,hausdorff_mm,max_deviation_mm\n";
    for (const auto& r : rows)
        csv << r.knots << ',' << seriesName(r.refiner) << ',' << fixed(r.refinedHausdorff_mm, 4)
            << ',' << fixed(r.hausdorff_mm, 4) << ',' << fixed(r.maxDeviation_mm, 4) << '\n';
    writeText(out / "fig12_all.csv", csv.str());
    mdRows("all, refined Hausdorff", pooledBlades, rows,
           &synth::RefinerComparisonRow::refinedHausdorff_mm);
    mdRows("all, polyline Hausdorff", pooledBlades, rows,
           &synth::RefinerComparisonRow::hausdorff_mm);
    writeText(out / "fig12.md", md.str());
    chart(out / "fig12_all.csv", out / "fig12.png",
          "Fan and Sheng Fig. 12 on captured skeletons (" + std::to_string(pooledBlades) +
              " blades, 128 knots refined)",
          "knots", "refined_hausdorff_mm", "refiner", "knots kept (of 128, log scale)",
          "refined Hausdorff error (mm, mean over frames and blades)", "logx");
}

}  // namespace meadow::bench
