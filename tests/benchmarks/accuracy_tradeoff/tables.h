#pragma once
// The accuracy / trade-off bench's thirteen tables, each written under `out` as CSV and Markdown
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
// Keeps the fit's skeleton (at most a few per preset: each costs seconds of Hausdorff).
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

// 8. segmentation_fusion.csv/.md: blade-type preset x fused frames (median, nearest recurring):
// recall and median IoU plain, with a perfect partition of the found mask and with a pixel's
// tolerance.
void segmentationOverFusion(const Plan& plan, const std::filesystem::path& out);

// 9. segmentation_missed.csv/.md: what the sensor leaves of the blades segmentation misses (read
// on under half, flush on a neighbour) and the recall bound that follows, per preset and frames.
void segmentationMissed(const Plan& plan, const std::filesystem::path& out);

// 10. segmentation_ablation.csv/.md: recall / median IoU with one sensor noise term off at a time.
void segmentationAblation(const Plan& plan, const std::filesystem::path& out);

// 11. tracks_fusion.csv/.md: tracked tip RMS from capture's 4 groups of 3 frames against one
// segmentation of all 12 fused by their nearest recurring readings.
void tracksOverFusion(const Plan& plan, const std::filesystem::path& out);

// 12. tip_reach.csv/.md: how far the readings reach toward each true tip over 12 frames, and
// where unextended tracked tips stop.
void tipReach(const Plan& plan, const std::filesystem::path& out);

// 13. motion_calibration.csv/.md: the motion test on every preset and on gentler winds.
void motionCalibration(const Plan& plan, const std::filesystem::path& out);

}  // namespace meadow::bench
