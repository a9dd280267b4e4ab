#pragma once
// The refiners of Fan & Sheng 2017 compared as in their Fig. 12: refined error against knot
// count for movement similarity (Algorithm 1) and its three baselines (random, mean,
// geometry only), scored by the refined Hausdorff error (Eq. 4, Algorithm 2).
#include <filesystem>
#include <glm/vec3.hpp>
#include <vector>

#include "meadow/modeling/skeleton_refiner.h"

namespace meadow::synth {

using modeling::KnotTrajectories;
using modeling::RefinerKind;
using modeling::RefinerParams;

// One row of the Fig. 12 comparison: errors of a refiner at a knot count, averaged over blades
// (and, for the random refiner, over `randomTrials` seeds).
struct RefinerComparisonRow {
    int knots = 0;
    RefinerKind refiner = RefinerKind::MovementSimilarity;
    float refinedHausdorff_mm = 0.f;  // Algorithm 2, mean over frames and blades
    float hausdorff_mm = 0.f;         // symmetric polyline distance, worst frame, mean over blades
    float maxDeviation_mm = 0.f;      // worst frame, mean over blades
};
// Runs every refiner at every knot count on each blade (rest knots + its trajectories).
std::vector<RefinerComparisonRow> compareRefiners(
    const std::vector<std::vector<glm::vec3>>& restKnots,
    const std::vector<KnotTrajectories>& trajectories, const std::vector<int>& knotCounts,
    const RefinerParams& params = {}, int randomTrials = 10);
// CSV (header: knots,refiner,refined_hausdorff_mm,hausdorff_mm,max_deviation_mm), written
// atomically. Throws meadow::Error naming the path when it cannot be written.
void writeRefinerComparisonCsv(const std::filesystem::path& path,
                               const std::vector<RefinerComparisonRow>& rows);

}  // namespace meadow::synth
