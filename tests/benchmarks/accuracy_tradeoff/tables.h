#pragma once
// The accuracy / trade-off bench's seven tables, each written under `out` as CSV and Markdown
// (and PNG charts where named): accuracy_tradeoff_bench.cpp runs them in this order.
#include <filesystem>
#include <glm/vec3.hpp>
#include <map>
#include <string>
#include <vector>

#include "accuracy_tradeoff/plan.h"
#include "accuracy_tradeoff/scene.h"
#include "meadow/modeling/blade_fit.h"

namespace meadow::bench {

// 1. segmentation_accuracy.csv/.md: preset x noise, recall, precision, median IoU, flags.
void segmentationAccuracy(const Plan& plan, const std::filesystem::path& out);

// 2. capture_tradeoff.csv/.md/.png: median IoU against segmentation time (fusion frames, the
// partition's contour sigma, plane fit).
void captureTradeoff(const Plan& plan, const std::vector<Scene>& scenes,
                     const std::filesystem::path& out);

// The skeletons the modeling accuracy run fitted, per preset, in blade-local frames: Fig. 12's
// input.
struct Fig12Input {
    std::map<std::string, std::vector<std::vector<glm::vec3>>> restKnots;
};
// Keeps the fit's skeleton (at most a few per preset: each costs ~1.5 s of Hausdorff).
void appendFig12Skeleton(Fig12Input& input, const std::string& preset,
                         const modeling::BladeFit& fit);

// 3. modeling_accuracy.csv/.md: blade type x noise x distance, spine / tip / height / width
// errors of the fitted archetypes; fills `fig12` with the nominal-noise skeletons.
void modelingAccuracy(const Plan& plan, const std::filesystem::path& out, Fig12Input& fig12);

// 4. modeling_tradeoff.csv/.md/.png (+ _knots, _width): spine error against capture time per
// tuft (refined knots, fusion frames, tolerance).
void modelingTradeoff(const Plan& plan, const std::vector<Scene>& scenes,
                      const std::filesystem::path& out);

// 5. fig12_<preset>.csv, fig12_all.csv, fig12.md, fig12.png: Fan & Sheng 2017 Fig. 12 on the
// captured skeletons.
void fig12(const Fig12Input& input, const std::filesystem::path& out);

// 6. segmentation_distance.csv/.md/.png: blade-type preset x camera distance at nominal noise,
// one frame: recall, precision, median IoU (where the segmentation works, and where not).
void segmentationOverDistance(const Plan& plan, const std::filesystem::path& out);

// 7. modeling_groups.csv/.md/.png (+ _per_blade.csv, the chart's rows): blade-type preset x fused
// groups (1, 2, 4, 8 groups of capture's fused frames) at nominal noise: each blade fitted once to
// the mean of its skeletons across groups (blade_tracks.h), its tip, height and width errors and
// the CPU per tuft.
void modelingOverGroups(const Plan& plan, const std::filesystem::path& out);

}  // namespace meadow::bench
