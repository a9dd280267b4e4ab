#pragma once
// Errors of a refined skeleton against the full one, over simulated frames.
#include <glm/vec3.hpp>
#include <vector>

#include "meadow/modeling/chain_simulation.h"

namespace meadow::modeling {

// Refined Hausdorff distance of one frame (Fan & Sheng 2017, Eq. 4 / Algorithm 2): the largest
// distance from a culled knot to its nearest kept knot. `kept` are indices into `knots`,
// ascending. 0 when nothing was culled.
float refinedHausdorff_m(const std::vector<glm::vec3>& knots, const std::vector<int>& kept);

// Distance from p to segment [a, b].
float pointSegmentDistance_m(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b);
// Largest distance from a point of polyline `from` to polyline `to`. Each segment of `from` is
// probed at its vertices and `samplesPerSegment - 1` interior points (the distance to a polyline
// can peak inside a segment). Requires non-empty polylines.
float directedHausdorff_m(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to,
                          int samplesPerSegment = 8);
// Symmetric Hausdorff distance between two polylines: max of both directed distances.
float hausdorff_m(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b,
                  int samplesPerSegment = 8);

struct RefinementError {
    float refinedHausdorffMean_m = 0.f;  // Algorithm 2 per frame, averaged over frames (Fig. 12)
    float refinedHausdorffMax_m = 0.f;   // ... its worst frame
    float hausdorffMax_m = 0.f;          // symmetric full-vs-refined polyline distance, worst frame
    float maxDeviation_m = 0.f;  // largest distance of a full knot from the refined polyline
};
// Evaluates a refinement (kept knot indices, ascending) over every frame of the trajectories.
RefinementError evaluateRefinement(const KnotTrajectories& frames, const std::vector<int>& kept);
// RefinementError::maxDeviation_m alone (the cheap part: no polyline Hausdorff distance).
float maxDeviation_m(const KnotTrajectories& frames, const std::vector<int>& kept);

}  // namespace meadow::modeling
