#include "segmentation/scene_planes.h"

#include <pcl/ModelCoefficients.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <sstream>

namespace meadow::capture::segmentation::scene {

namespace {

constexpr int kRansacSeed = 4321;  // the same planes run to run
constexpr int kRansacIterations = 300;
constexpr int kRansacStride_px = 4;  // planes are fitted on every 4th pixel of every 4th row
// A plane of the room is wide in both directions: the second largest standard deviation of its
// inliers reaches this. The widest leaf lies far below it (maize: a 10 cm leaf has about 3 cm);
// a floor or wall in view far above.
constexpr float kMinPlaneSpread_m = 0.12f;
constexpr double kMinPlaneFill = 0.25;
// A plane's readings spread with depth: a Kinect's disparity steps are z^2 / 345 m apart, 46 mm
// at 4 m. Its inliers are taken within scenePlaneDistance_m + this z^2, about three steps beyond
// the near tolerance, or a far wall leaves slivers a plant's width.
constexpr float kPlaneToleranceGrowth_per_m = 0.01f;

// Which planes can bear a plant: the camera is held upright (its roll under 30 deg) and looks
// level or down (README, "Place the camera"), so a floor's, table top's or the ground's normal,
// turned towards the camera, leans sideways at most sin 30 deg and does not point down the
// image (beyond sin 6 deg: a camera tilted a little up). Walls beside the camera do not bear.
constexpr float kMaxBearingSideLean = 0.5f;
constexpr float kMaxBearingDownLean = 0.1f;

pcl::PointCloud<pcl::PointXYZ>::Ptr cloudOf(const std::vector<Sample>& s) {
    auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    cloud->reserve(s.size());
    for (const Sample& e : s) cloud->push_back({e.p.x, e.p.y, e.p.z});
    return cloud;
}

// Second largest standard deviation of the points: how wide a plane's inliers spread.
float secondSpread_m(const pcl::PointCloud<pcl::PointXYZ>& cloud, const pcl::Indices& indices) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto i : indices)
        mean += cloud[static_cast<std::size_t>(i)].getVector3fMap().cast<double>();
    mean /= static_cast<double>(indices.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto i : indices) {
        const Eigen::Vector3d d =
            cloud[static_cast<std::size_t>(i)].getVector3fMap().cast<double>() - mean;
        cov += d * d.transpose();
    }
    cov /= static_cast<double>(indices.size());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
    return static_cast<float>(std::sqrt(std::max(0.0, solver.eigenvalues()[1])));
}

}  // namespace

float planeTolerance_m(float base_m, float z_m) {
    return base_m + kPlaneToleranceGrowth_per_m * z_m * z_m;
}

std::vector<Sample> samples(const cv::Mat1w& depth_mm, const cv::Mat1b& mask, const Intrinsics& k,
                            int stride) {
    std::vector<Sample> out;
    for (int y = 0; y < depth_mm.rows; y += stride)
        for (int x = 0; x < depth_mm.cols; x += stride) {
            if (!mask(y, x)) continue;
            const glm::vec3 v = k.backProject(static_cast<float>(x), static_cast<float>(y),
                                              depth_mm(y, x) / kMillimetresPerMetre);
            out.push_back({{x, y}, v});
        }
    return out;
}

float medianDepth_m(const std::vector<Sample>& s) {
    std::vector<float> depths;
    depths.reserve(s.size());
    for (const Sample& e : s) depths.push_back(e.p.z);
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    return depths[depths.size() / 2];
}

float planeDistance_m(const ScenePlane& c, const glm::vec3& v) {
    return std::abs(c[0] * v.x + c[1] * v.y + c[2] * v.z + c[3]);
}

bool bearsThings(const ScenePlane& c) {
    const float towardsCamera = c[3] >= 0.f ? 1.f : -1.f;
    return towardsCamera * c[1] <= kMaxBearingDownLean && std::abs(c[0]) <= kMaxBearingSideLean;
}

float aboveBearing_m(const cv::Mat1b& part, const cv::Mat1w& depth_mm, const Intrinsics& k,
                     const std::vector<ScenePlane>& planes) {
    std::vector<ScenePlane> bearing;
    std::copy_if(planes.begin(), planes.end(), std::back_inserter(bearing), bearsThings);
    float nearest = std::numeric_limits<float>::infinity();
    if (bearing.empty()) return nearest;
    const cv::Rect box = cv::boundingRect(part);
    for (int y = box.y; y < box.y + box.height; ++y)
        for (int x = box.x; x < box.x + box.width; ++x) {
            if (!part(y, x) || depth_mm(y, x) == 0) continue;
            const glm::vec3 v = k.backProject(static_cast<float>(x), static_cast<float>(y),
                                              depth_mm(y, x) / kMillimetresPerMetre);
            for (const ScenePlane& plane : bearing)
                nearest = std::min(nearest, planeDistance_m(plane, v));
        }
    return nearest;
}

std::vector<ScenePlane> removeScenePlanes(const cv::Mat1w& depth_mm, const Intrinsics& k,
                                          const SegmenterParams& p, cv::Mat1b& rest,
                                          StageReport& report) {
    std::vector<ScenePlane> removed;
    std::vector<Sample> s = samples(depth_mm, rest, k, kRansacStride_px);
    const std::size_t all = s.size();
    for (int attempt = 0; attempt < p.maxScenePlanes; ++attempt) {
        if (attempt > 0) s = samples(depth_mm, rest, k, kRansacStride_px);
        if (s.size() < 100) break;
        const auto cloud = cloudOf(s);
        pcl::SACSegmentation<pcl::PointXYZ> fit;
        fit.setModelType(pcl::SACMODEL_PLANE);
        fit.setMethodType(pcl::SAC_RANSAC);
        fit.setDistanceThreshold(planeTolerance_m(p.scenePlaneDistance_m, medianDepth_m(s)));
        fit.setMaxIterations(kRansacIterations);
        fit.setInputCloud(cloud);
        srand(kRansacSeed + attempt);  // PCL's RANSAC draws from rand()
        pcl::PointIndices inliers;
        pcl::ModelCoefficients c;
        fit.segment(inliers, c);
        const double share = static_cast<double>(inliers.indices.size()) / all;
        if (c.values.size() != 4 || share < p.minScenePlaneShare) break;
        const float spread = secondSpread_m(*cloud, inliers.indices);
        // A floor or wall fills the part of the image it spans (bar what stands before it); a
        // plane through the leaves of a large plant catches pieces of several of them.
        std::vector<cv::Point> inlierPixels;
        for (const auto i : inliers.indices)
            inlierPixels.push_back(s[static_cast<std::size_t>(i)].px);
        const cv::Rect span = cv::boundingRect(inlierPixels);
        const double fill = static_cast<double>(inlierPixels.size()) * kRansacStride_px *
                            kRansacStride_px / std::max(1, span.area());
        if (spread < kMinPlaneSpread_m || fill < kMinPlaneFill) {
            report.notes.push_back("kept a plane of " + std::to_string(std::lround(100 * share)) +
                                   " % of the points: too narrow or too broken for a floor or "
                                   "wall");
            break;
        }
        const ScenePlane plane{c.values[0], c.values[1], c.values[2], c.values[3]};
        int cleared = 0;
        for (int y = 0; y < depth_mm.rows; ++y)
            for (int x = 0; x < depth_mm.cols; ++x) {
                if (!rest(y, x)) continue;
                const glm::vec3 v = k.backProject(static_cast<float>(x), static_cast<float>(y),
                                                  depth_mm(y, x) / kMillimetresPerMetre);
                if (planeDistance_m(plane, v) <= planeTolerance_m(p.scenePlaneDistance_m, v.z)) {
                    rest(y, x) = 0;
                    ++cleared;
                }
            }
        std::ostringstream note;
        note.precision(2);
        note << "scene plane n=(" << c.values[0] << ", " << c.values[1] << ", " << c.values[2]
             << ") removed: " << cleared << " px";
        report.notes.push_back(note.str());
        removed.push_back(plane);
    }
    return removed;
}

}  // namespace meadow::capture::segmentation::scene
