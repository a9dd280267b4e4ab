#pragma once
// What the accuracy / trade-off bench measures: presets, noise scales, distances, seeds and
// repetitions (accuracy_tradeoff_bench.cpp), shared by its tables.
#include <string>
#include <vector>

namespace meadow::bench {

inline const std::vector<std::string> kBladeTypePresets{"slim-grass", "quadratic-leaf",
                                                        "shrub-leaf", "bamboo-leaf", "sharp-tip"};
inline const std::vector<float> kNoiseScales{0.f, 1.f, 2.f, 4.f};
inline constexpr float kNominalNoise = 1.f;
inline const std::vector<float> kModelingDistances_m{0.6f, 0.8f, 1.0f};
// `meadow synth --distance` allows 0.5-1.2 m.
inline const std::vector<float> kSegmentationDistances_m{0.5f, 0.6f, 0.8f, 1.0f, 1.2f};
inline constexpr int kMaxFusionFrames = 12;  // frames rendered per trade-off scene
inline constexpr float kMillimetresPerMetre = 1000.f;
inline constexpr double kPercent = 100.0;

struct Plan {
    std::vector<std::string> segmentationPresets;  // every preset of `meadow synth --list`
    std::vector<std::string> bladeTypes = kBladeTypePresets;
    std::vector<float> noises = kNoiseScales;
    std::vector<float> distances_m = kModelingDistances_m;
    std::vector<float> segmentationDistances_m = kSegmentationDistances_m;
    int segmentationSeeds = 5;
    int modelingSeeds = 2;
    int tradeoffSeeds = 2;
    int repetitions = 5;
    // Fused frames of a still tuft, by median and by nearest recurring reading (1: no fusion).
    std::vector<int> fusionFrames{1, 3, 5, 8, 12, 16};
    int fusionSeeds = 10;  // segmentation_fusion and segmentation_missed
    std::vector<int> missedFrames{1, 8, 12};
    int ablationSeeds = 2;  // segmentation_ablation
    int trackSeeds = 2;     // tracks_fusion and tip_reach, at distances_m
    int motionSeeds = 3;    // motion_calibration
    std::vector<float> gentlerWinds{0.f, 0.005f, 0.01f, 0.02f, 0.05f, 0.1f, 0.3f};
    bool verbose = false;  // one line per fitted blade in the modeling accuracy run
};

// The full plan, or with `quick` fewer presets, seeds and repetitions (a smoke run).
Plan makePlan(bool quick);

}  // namespace meadow::bench
