// The Fig. 12 comparison of Fan & Sheng 2017: refined error against knot count for the four
// refiners, and its CSV.
#include "meadow/synth/refiner_comparison.h"

#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "meadow/core/atomic_file.h"
#include "meadow/modeling/hausdorff.h"

namespace meadow::synth {

using namespace modeling;

std::vector<RefinerComparisonRow> compareRefiners(
    const std::vector<std::vector<glm::vec3>>& restKnots,
    const std::vector<KnotTrajectories>& trajectories, const std::vector<int>& knotCounts,
    const RefinerParams& params, int randomTrials) {
    if (restKnots.size() != trajectories.size() || restKnots.empty())
        throw std::invalid_argument(
            "compareRefiners: need one trajectory set per blade, and >= 1 blade");
    if (randomTrials < 1) throw std::invalid_argument("compareRefiners: randomTrials must be >= 1");
    constexpr float kMillimetresPerMetre = 1000.f;
    std::vector<RefinerComparisonRow> rows;
    for (int m : knotCounts) {
        for (RefinerKind kind : {RefinerKind::MovementSimilarity, RefinerKind::Random,
                                 RefinerKind::Mean, RefinerKind::GeometryOnly}) {
            RefinerComparisonRow row{.knots = m, .refiner = kind};
            const int trials = kind == RefinerKind::Random ? randomTrials : 1;
            for (std::size_t b = 0; b < restKnots.size(); ++b) {
                for (int trial = 0; trial < trials; ++trial) {
                    RefinerParams p = params;
                    p.seed = params.seed + static_cast<std::uint64_t>(trial) * 7919u + b;
                    const RefinementError e = evaluateRefinement(
                        trajectories[b], refine(kind, restKnots[b], trajectories[b], m, p));
                    row.refinedHausdorff_mm += e.refinedHausdorffMean_m;
                    row.hausdorff_mm += e.hausdorffMax_m;
                    row.maxDeviation_mm += e.maxDeviation_m;
                }
            }
            const float scale =
                kMillimetresPerMetre /
                static_cast<float>(restKnots.size() * static_cast<std::size_t>(trials));
            row.refinedHausdorff_mm *= scale;
            row.hausdorff_mm *= scale;
            row.maxDeviation_mm *= scale;
            rows.push_back(row);
        }
    }
    return rows;
}

void writeRefinerComparisonCsv(const std::filesystem::path& path,
                               const std::vector<RefinerComparisonRow>& rows) {
    std::ostringstream csv;
    csv << "knots,refiner,refined_hausdorff_mm,hausdorff_mm,max_deviation_mm\n"
        << std::fixed << std::setprecision(4);
    for (const RefinerComparisonRow& r : rows)
        csv << r.knots << ',' << toString(r.refiner) << ',' << r.refinedHausdorff_mm << ','
            << r.hausdorff_mm << ',' << r.maxDeviation_mm << '\n';
    writeFileAtomically(path, csv.str());
}

}  // namespace meadow::synth
