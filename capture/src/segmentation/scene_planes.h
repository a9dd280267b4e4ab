#pragma once
// The scene's readings and its large planes (floor, walls, table tops), for finding a plant
// among them (plant_finding.cpp): the planes are fitted with PCL's RANSAC on a sample of the
// readings and removed; those a pot can stand on are told from walls.
#include <array>
#include <glm/vec3.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation::scene {

// One reading of a sampling grid: its pixel and its camera-space point (metres).
struct Sample {
    cv::Point px;
    glm::vec3 p;
};

// The readings of `mask` on every `stride`-th pixel of every `stride`-th row.
std::vector<Sample> samples(const cv::Mat1w& depth_mm, const cv::Mat1b& mask, const Intrinsics& k,
                            int stride);

// The median depth of the samples (not empty).
float medianDepth_m(const std::vector<Sample>& s);

// `base_m` near the camera, grown with the depth squared as a sensor's readings scatter (a
// Kinect's disparity steps are z^2 / 345 m apart): the tolerance of the planes, of the clusters'
// reach, and of the gap between a plant's pieces.
float planeTolerance_m(float base_m, float z_m);

using ScenePlane = std::array<float, 4>;  // n.x + d = 0

float planeDistance_m(const ScenePlane& c, const glm::vec3& v);

// A floor, table top or the ground, not a wall beside the camera or a ceiling: the camera is
// held upright and looks level or down (README, "Place the camera"). Image y runs down; the
// normal is turned to the camera's side (d > 0). (A wall ahead of a level camera passes too: it
// cannot be told from the ground below one that looks straight down.)
bool bearsThings(const ScenePlane& c);

// How far above what bears things (a floor, a table top, the ground) the nearest reading of
// `part` lies: a pot stands on one; the thick base of a piece of leaf broken off higher up does
// not. Infinity with nothing in view that bears things.
float aboveBearing_m(const cv::Mat1b& part, const cv::Mat1w& depth_mm, const Intrinsics& k,
                     const std::vector<ScenePlane>& planes);

// Removes the room's large planes from `rest` (every pixel within the tolerance of one, at most
// SegmenterParams::maxScenePlanes of them); returns them.
std::vector<ScenePlane> removeScenePlanes(const cv::Mat1w& depth_mm, const Intrinsics& k,
                                          const SegmenterParams& p, cv::Mat1b& rest,
                                          StageReport& report);

}  // namespace meadow::capture::segmentation::scene
