#pragma once
// Skeleton refining by movement similarity (Fan & Sheng 2017, Sec. 4.4, Eq. 1-3, Algorithm 1)
// and the paper's three baselines (their Fig. 12): random, mean (even along the skeleton) and
// geometry-only (merge the shortest edge). Every refiner returns the indices of the kept knots,
// ascending, the first and last knot always among them.
#include <cstdint>
#include <filesystem>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "meadow/core/enum_names.h"
#include "meadow/modeling/chain_simulation.h"

namespace meadow::modeling {

// Mean distance between two knots over the n frames, Fan & Sheng 2017, Eq. 1:
//   dis = 1/n sum_t |p_a(t) - p_b(t)|.
float meanDistance_m(const KnotTrajectories& frames, int a, int b);
// Movement variance of two knots, Fan & Sheng 2017, Eq. 2-3, computed as a variance: the
// population variance over the frames of the relative position r(t) = p_b(t) - p_a(t),
//   r_mean = 1/n sum_t r(t)  (Eq. 2),   var = 1/n sum_t |r(t) - r_mean|^2  (Eq. 3), in m^2.
// Zero when the two knots move rigidly together (pure translation).
float movementVariance_m2(const KnotTrajectories& frames, int a, int b);
// Movement difference, Fan & Sheng 2017, Eq. 1-3 combined: D = mu dis + (1 - mu) var.
// Departure: dis (m) and var (m^2) are each divided by a scale (their mean over the full chain's
// adjacent pairs) before mixing, so that mu weighs two dimensionless terms and does not depend
// on the unit or on the blade's size. The paper mixes them as they are.
float movementDifference(float dis, float var, float mu, float disScale, float varScale);

struct RefinerParams {
    // Weight of the distance term. 0.5 weighs spacing and relative motion equally
    // (see docs/capture.md#refining).
    float mu = 0.5f;
    std::uint64_t seed = 1;  // random refiner only
};

// Fan & Sheng 2017, Algorithm 1: while more than m knots remain, find the adjacent kept pair of
// least movement difference D and merge it. Merging keeps one knot of the pair: the endpoint if
// either is one, otherwise the one whose removal leaves the smaller D to the new neighbour.
// Requires m >= 2 and frames with >= 2 knots each, all frames the same size.
std::vector<int> refineByMovementSimilarity(const KnotTrajectories& frames, int m,
                                            const RefinerParams& params = {});
// The same greedy steps run down to the two ends: the knots in the order Algorithm 1 drops them.
// The steps do not depend on m, so keptAfterDrops(n, order, m) is refineByMovementSimilarity(
// frames, m) for every m, from one run (the knot-count search under a tolerance uses it).
std::vector<int> movementSimilarityDropOrder(const KnotTrajectories& frames,
                                             const RefinerParams& params = {});
// The knots 0..knotCount-1 left, ascending, once the first knotCount - m of `dropOrder` are gone.
std::vector<int> keptAfterDrops(int knotCount, const std::vector<int>& dropOrder, int m);
// Baselines on the rest (or any one frame's) knots.
std::vector<int> refineRandom(int knotCount, int m, std::uint64_t seed);
std::vector<int> refineMean(const std::vector<glm::vec3>& knots, int m);
std::vector<int> refineGeometryOnly(const std::vector<glm::vec3>& knots, int m);

enum class RefinerKind { MovementSimilarity, Random, Mean, GeometryOnly };
inline constexpr EnumNames<RefinerKind, 4> kRefinerKindNames{{{
    {RefinerKind::MovementSimilarity, "movement_similarity"},
    {RefinerKind::Random, "random"},
    {RefinerKind::Mean, "mean"},
    {RefinerKind::GeometryOnly, "geometry_only"},
}}};
inline std::string toString(RefinerKind kind) { return std::string(kRefinerKindNames.name(kind)); }
std::vector<int> refine(RefinerKind kind, const std::vector<glm::vec3>& restKnots,
                        const KnotTrajectories& frames, int m, const RefinerParams& params = {});

}  // namespace meadow::modeling
