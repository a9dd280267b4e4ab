// Fan & Sheng 2017, Fig. 12 on simulated blades: refined Hausdorff error against knot count for
// movement similarity and its three baselines. On the paper's refined Hausdorff metric (culled
// knot to nearest kept knot) movement similarity beats the random refiner, not even spacing,
// which minimises the largest gap by construction; on the symmetric Hausdorff distance (the
// shape actually lost) it is the best of the four. The bench's fig12 table holds the curves.
#include "meadow/synth/refiner_comparison.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "meadow/modeling/chain_simulation.h"
#include "meadow/modeling/quadratic_bezier.h"
#include "meadow/modeling/skeleton.h"
#include "support/test_util.h"

namespace meadow::synth {
namespace {

constexpr int kFullKnots = 128;  // Fan & Sheng's Fig. 12 starts from 128 knots

// A rest skeleton in the blade-local frame: a quadratic Bezier resampled to kFullKnots knots.
std::vector<glm::vec3> restSkeleton(float height_m, float bend) {
    const modeling::QuadraticBezier b{
        {0.f, 0.f, 0.f},
        {0.05f * bend * height_m, 0.55f * height_m, 0.f},
        {bend * height_m, (1.f - 0.5f * bend * bend) * height_m, 0.f}};
    std::vector<glm::vec3> dense;
    for (int i = 0; i <= 1000; ++i) dense.push_back(b.at(i / 1000.f));
    return modeling::resampleByArcLength(dense, kFullKnots);
}

TEST(RefinerComparison, Fig12MovementSimilarityAgainstBaselines) {
    std::vector<std::vector<glm::vec3>> rest;
    std::vector<KnotTrajectories> frames;
    int seed = 1;
    for (float height : {0.08f, 0.15f, 0.3f})
        for (float bend : {0.2f, 0.6f}) {
            rest.push_back(restSkeleton(height, bend));
            modeling::ChainSimulationParams p;
            p.seed = static_cast<std::uint64_t>(seed++);
            frames.push_back(modeling::simulateChain(rest.back(), p));
        }
    constexpr int kRandomTrials = 4;
    const auto rows = compareRefiners(rest, frames, {64, 32, 16, 8}, {}, kRandomTrials);
    std::map<RefinerKind, RefinerComparisonRow> at16;
    for (const auto& r : rows)
        if (r.knots == 16) at16[r.refiner] = r;
    const RefinerComparisonRow& ms = at16[RefinerKind::MovementSimilarity];
    // The paper's metric: better than random.
    EXPECT_LT(ms.refinedHausdorff_mm, at16[RefinerKind::Random].refinedHausdorff_mm);
    // Shape lost: not worse than any baseline.
    for (RefinerKind k : {RefinerKind::Random, RefinerKind::Mean, RefinerKind::GeometryOnly})
        EXPECT_LE(ms.hausdorff_mm, at16[k].hausdorff_mm) << toString(k);

    const std::filesystem::path csv = test::freshTempDir("refiner_comparison") / "fig12.csv";
    writeRefinerComparisonCsv(csv, rows);
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, "knots,refiner,refined_hausdorff_mm,hausdorff_mm,max_deviation_mm");
}

}  // namespace
}  // namespace meadow::synth
