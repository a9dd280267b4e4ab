// Finding the plant in a scene (PlantFinding::Clusters): the large planes of the room (floor,
// walls, table tops) are fitted with PCL's RANSAC and removed, what remains is split into
// Euclidean clusters (PCL), and the plant is the thin-parted cluster the camera is aimed at.
// Its pot, the thick part it stands in at its bottom, is removed. A scene where no cluster is
// thin enough to be leaves has no plant.
#include <pcl/ModelCoefficients.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/search/organized.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {

constexpr int kRansacSeed = 4321;  // the same planes run to run
constexpr int kRansacIterations = 300;
constexpr int kRansacStride_px = 4;   // planes are fitted on every 4th pixel of every 4th row
constexpr int kClusterStride_px = 2;  // clusters are found on every 2nd pixel of every 2nd row
// A plane of the room is wide in both directions: the second largest standard deviation of its
// inliers reaches this. The widest leaf lies far below it (maize: a 10 cm leaf has about 3 cm);
// a floor or wall in view far above.
constexpr float kMinPlaneSpread_m = 0.12f;
constexpr double kMinPlaneFill = 0.25;
// A plane's readings spread with depth: a Kinect's disparity steps are z^2 / 345 m apart, 46 mm
// at 4 m. Its inliers are taken within scenePlaneDistance_m + this z^2, about three steps beyond
// the near tolerance, or a far wall leaves slivers a plant's width.
constexpr float kPlaneToleranceGrowth_per_m = 0.01f;
// What the plane removal leaves of a floor or wall, along its borders and where its readings
// spread beyond the tolerance, lies within a few tolerances of it; a plant stands out of the
// floor and before the wall. A cluster with most of its pixels this close to a removed plane is
// a remnant, not an object.
constexpr float kRemnantTolerances = 2.f;
constexpr float kMaxRemnantShare = 0.6f;
// How far apart two pieces of one plant lie, near the camera. What parts them is what the
// sensor did not read between them, or read as a jump; both widen as its readings scatter, with
// depth squared, so the reach grows as a plane's tolerance does (7.8 cm at 2.2 m).
constexpr float kLeafGap_m = 0.03f;
// A depth jump spans this many of the sensor's 90th-percentile neighbour steps, at least.
constexpr float kJumpSteps = 2.f;
// A piece that joins the plant is held to less: slivers of the floor and wall beside the plant
// lie within its reach.
constexpr float kMaxJoinedRemnantShare = 0.2f;
// A pot stands on the floor, a table top or the ground: its lowest reading lies within this of
// it (a camera looking down sees its bottom rim hidden, the plane's removal takes a few cm).
// A broad leaf's base in a piece of the plant that broke off lies well above.
constexpr float kPotStandsWithin_m = 0.2f;
// The objects left out that the debug overlay outlines: the largest, down to an eighth of what a
// plant covers at least.
constexpr std::size_t kMaxLeftOut = 12;
constexpr int kLeftOutShareOfPlant = 8;
// What a user whose plant is thin but only too small (over half a plant's pixels) should do.
constexpr const char* kBringCloser = ": bring the camera closer if it is the plant";

float planeTolerance_m(float base_m, float z_m) {
    return base_m + kPlaneToleranceGrowth_per_m * z_m * z_m;
}

// Which planes can bear a plant: the camera is held upright (its roll under 30 deg) and looks
// level or down (README, "Place the camera"), so a floor's, table top's or the ground's normal,
// turned towards the camera, leans sideways at most sin 30 deg and does not point down the
// image (beyond sin 6 deg: a camera tilted a little up). Walls beside the camera do not bear.
constexpr float kMaxBearingSideLean = 0.5f;
constexpr float kMaxBearingDownLean = 0.1f;

struct Sample {
    cv::Point px;
    pcl::PointXYZ p;
};

std::vector<Sample> samples(const cv::Mat1w& depth_mm, const cv::Mat1b& mask, const Intrinsics& k,
                            int stride) {
    std::vector<Sample> out;
    for (int y = 0; y < depth_mm.rows; y += stride)
        for (int x = 0; x < depth_mm.cols; x += stride) {
            if (!mask(y, x)) continue;
            const glm::vec3 v = k.backProject(static_cast<float>(x), static_cast<float>(y),
                                              depth_mm(y, x) / kMillimetresPerMetre);
            out.push_back({{x, y}, {v.x, v.y, v.z}});
        }
    return out;
}

// The median depth of the samples (not empty).
float medianDepth_m(const std::vector<Sample>& s) {
    std::vector<float> depths;
    depths.reserve(s.size());
    for (const Sample& e : s) depths.push_back(e.p.z);
    std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
    return depths[depths.size() / 2];
}

pcl::PointCloud<pcl::PointXYZ>::Ptr cloudOf(const std::vector<Sample>& s) {
    auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    cloud->reserve(s.size());
    for (const Sample& e : s) cloud->push_back(e.p);
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

using ScenePlane = std::array<float, 4>;  // n.x + d = 0

float planeDistance_m(const ScenePlane& c, const glm::vec3& v) {
    return std::abs(c[0] * v.x + c[1] * v.y + c[2] * v.z + c[3]);
}

// A floor, table top or the ground, not a wall beside the camera or a ceiling: see
// kMaxBearingSideLean. Image y runs down; the normal is turned to the camera's side (d > 0).
// (A wall ahead of a level camera passes too: it cannot be told from the ground below one that
// looks straight down.)
bool bearsThings(const ScenePlane& c) {
    const float towardsCamera = c[3] >= 0.f ? 1.f : -1.f;
    return towardsCamera * c[1] <= kMaxBearingDownLean && std::abs(c[0]) <= kMaxBearingSideLean;
}

// How far above what bears things (a floor, a table top, the ground) the nearest reading of
// `part` lies: a pot stands on one; the thick base of a piece of leaf broken off higher up does
// not. Infinity with nothing in view that bears things.
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

// Removes the room's large planes from `rest` (every pixel within the tolerance of one);
// returns them.
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

struct Cluster {
    cv::Mat1b mask;  // frame-sized
    int area_px = 0;
    cv::Point2f centroid_px;
    float medianDepth_m = 0.f;
    float meanWidth_m = 0.f;
    float height_m = 0.f;
    float nearPlanes = 0.f;  // share of its pixels within kRemnantTolerances of a scene plane
    cv::Mat1b pot;           // the thick part at its bottom, removed from mask
    cv::Vec3f lo{1e9f, 1e9f, 1e9f}, hi{-1e9f, -1e9f, -1e9f};  // camera-space bounds of its samples
};

bool boundsMeet(const Cluster& a, const Cluster& b, float margin_m) {
    for (int i = 0; i < 3; ++i)
        if (a.lo[i] - margin_m > b.hi[i] || b.lo[i] - margin_m > a.hi[i]) return false;
    return true;
}

// How far apart the sensor puts neighbouring readings of one surface, per square metre of depth
// (stereo and structured-light steps grow as z squared): the 90th percentile over horizontal
// neighbours whose readings differ by under 10 % of their depth (not two surfaces), on every
// 2nd row.
float neighbourStep_mm_per_m2(const cv::Mat1w& depth_mm) {
    std::vector<float> steps;
    for (int y = 0; y < depth_mm.rows; y += 2)
        for (int x = 0; x + 1 < depth_mm.cols; ++x) {
            const int a = depth_mm(y, x), b = depth_mm(y, x + 1);
            if (a == 0 || b == 0) continue;
            const float z_m = static_cast<float>(a) / kMillimetresPerMetre;
            const float step = static_cast<float>(std::abs(b - a));
            if (step < 0.1f * static_cast<float>(a)) steps.push_back(step / (z_m * z_m));
        }
    if (steps.empty()) return 0.f;
    const auto at = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() * 9 / 10);
    std::nth_element(steps.begin(), at, steps.end());
    return *at;
}

// Pixels on a jump in depth, a neighbour nearer or farther by more than the tolerance there:
// where a sensor reads mixed ("flying") depths between a leaf and what lies behind it, which
// would chain the two into one cluster. The tolerance is `floor_mm`, or kJumpSteps of the frame's
// own steps (neighbourStep_mm_per_m2) at that depth where the sensor steps wider (a stereo camera
// two metres away steps 30 mm and more between neighbours).
cv::Mat1b depthJumps(const cv::Mat1w& depth_mm, const cv::Mat1b& rest, float floor_mm) {
    const float step = neighbourStep_mm_per_m2(depth_mm);
    cv::Mat1w nearest, farthest;
    const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, {3, 3});
    cv::Mat1w valid = depth_mm.clone();
    valid.setTo(std::numeric_limits<std::uint16_t>::max(), depth_mm == 0);
    cv::erode(valid, nearest, kernel);
    cv::dilate(depth_mm, farthest, kernel);
    cv::Mat1b jumps = cv::Mat1b::zeros(depth_mm.size());
    for (int y = 0; y < depth_mm.rows; ++y)
        for (int x = 0; x < depth_mm.cols; ++x) {
            if (!rest(y, x)) continue;
            const float z_m = static_cast<float>(depth_mm(y, x)) / kMillimetresPerMetre;
            const float tolerance_mm = std::max(floor_mm, kJumpSteps * step * z_m * z_m);
            if (depth_mm(y, x) - nearest(y, x) > tolerance_mm ||
                farthest(y, x) - depth_mm(y, x) > tolerance_mm)
                jumps(y, x) = 255;
        }
    return jumps;
}

// PCL's organized neighbour search with the camera's own projection. PCL estimates it from the
// points it searches, a few dozen of a pyramid's grid: on a plant alone, or a flat leaf, they
// are too few or all in one plane, the estimate goes wrong without a word and every point is
// found alone. The grid's projection is the camera's, scaled by the sampling stride.
class GridNeighbours : public pcl::search::OrganizedNeighbor<pcl::PointXYZ> {
public:
    GridNeighbours(const Intrinsics& k, int stride) {
        const float s = 1.f / static_cast<float>(stride);
        projection_matrix_ << k.fx_px * s, 0.f, k.cx_px * s, 0.f,  //
            0.f, k.fy_px * s, k.cy_px * s, 0.f,                    //
            0.f, 0.f, 1.f, 0.f;
        KR_ = projection_matrix_.topLeftCorner<3, 3>();
        KR_KRT_ = KR_ * KR_.transpose();
    }
    // As OrganizedNeighbor's, without estimating the projection.
    void setInputCloud(const PointCloudConstPtr& cloud,
                       const IndicesConstPtr& indices = IndicesConstPtr()) override {
        input_ = cloud;
        indices_ = indices;
        mask_.assign(input_->size(), indices_ && !indices_->empty() ? 0 : 1);
        if (indices_)
            for (const auto i : *indices_) mask_[static_cast<std::size_t>(i)] = 1;
    }
};

// Euclidean clusters of `rest` on a stride, each grown back to every pixel of `rest` beside its
// samples at a depth within the tolerance.
std::vector<Cluster> euclideanClusters(const cv::Mat1w& depth_mm, const Intrinsics& k,
                                       const SegmenterParams& p, const cv::Mat1b& rest) {
    const float nearTolerance_mm = p.clusterTolerance_m * kMillimetresPerMetre;
    const std::vector<Sample> s = samples(
        depth_mm, rest & ~depthJumps(depth_mm, rest, nearTolerance_mm), k, kClusterStride_px);
    std::vector<Cluster> out;
    if (s.empty()) return out;
    // The samples' grid as an organized cloud: PCL's organized neighbour search finds a point's
    // neighbours in its image window, where a k-d tree had to be built over them for every
    // frame. Only the samples are searched and clustered.
    const int gw = (depth_mm.cols + kClusterStride_px - 1) / kClusterStride_px;
    const int gh = (depth_mm.rows + kClusterStride_px - 1) / kClusterStride_px;
    auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>(static_cast<std::uint32_t>(gw),
                                                                  static_cast<std::uint32_t>(gh));
    cloud->is_dense = false;
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    for (pcl::PointXYZ& q : *cloud) q = {kNaN, kNaN, kNaN};
    auto indices = pcl::make_shared<pcl::Indices>();
    indices->reserve(s.size());
    std::vector<int> sampleOf(cloud->size(), -1);
    for (std::size_t i = 0; i < s.size(); ++i) {
        const int at = s[i].px.y / kClusterStride_px * gw + s[i].px.x / kClusterStride_px;
        indices->push_back(at);
        (*cloud)[static_cast<std::size_t>(at)] = s[i].p;
        sampleOf[static_cast<std::size_t>(at)] = static_cast<int>(i);
    }
    pcl::EuclideanClusterExtraction<pcl::PointXYZ> extraction;
    // Samples spread apart, and readings scatter, with depth: the tolerance grows as the plane
    // tolerance does, at the median depth of what is left.
    const float tolerance_m = planeTolerance_m(p.clusterTolerance_m, medianDepth_m(s));
    extraction.setClusterTolerance(tolerance_m);
    extraction.setMinClusterSize(p.minClusterPoints);
    extraction.setMaxClusterSize(static_cast<pcl::uindex_t>(s.size()));
    extraction.setSearchMethod(pcl::make_shared<GridNeighbours>(k, kClusterStride_px));
    extraction.setInputCloud(cloud);
    extraction.setIndices(indices);
    std::vector<pcl::PointIndices> found;
    extraction.extract(found);
    for (pcl::PointIndices& c : found)
        for (auto& i : c.indices) i = sampleOf[static_cast<std::size_t>(i)];

    // Label of each sample, on the sample grid.
    cv::Mat1i grid(gh, gw, 0);
    for (std::size_t c = 0; c < found.size(); ++c)
        for (const auto i : found[c].indices) {
            const cv::Point px = s[static_cast<std::size_t>(i)].px;
            grid(px.y / kClusterStride_px, px.x / kClusterStride_px) = static_cast<int>(c) + 1;
        }
    out.resize(found.size());
    for (Cluster& c : out) c.mask = cv::Mat1b::zeros(depth_mm.size());
    for (std::size_t c = 0; c < found.size(); ++c)
        for (const auto i : found[c].indices) {
            const pcl::PointXYZ& q = s[static_cast<std::size_t>(i)].p;
            for (int a = 0; a < 3; ++a) {
                out[c].lo[a] = std::min(out[c].lo[a], q.data[a]);
                out[c].hi[a] = std::max(out[c].hi[a], q.data[a]);
            }
        }
    const float tolerance_mm = tolerance_m * kMillimetresPerMetre;
    for (int y = 0; y < depth_mm.rows; ++y)
        for (int x = 0; x < depth_mm.cols; ++x) {
            if (!rest(y, x)) continue;
            const int gx = x / kClusterStride_px, gy = y / kClusterStride_px;
            int best = 0;
            float bestStep = tolerance_mm;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int sx = gx + dx, sy = gy + dy;
                    if (sx < 0 || sy < 0 || sx >= gw || sy >= gh || grid(sy, sx) == 0) continue;
                    const float step =
                        std::abs(static_cast<float>(depth_mm(y, x)) -
                                 depth_mm(sy * kClusterStride_px, sx * kClusterStride_px));
                    if (step <= bestStep) best = grid(sy, sx), bestStep = step;
                }
            if (best > 0) out[static_cast<std::size_t>(best - 1)].mask(y, x) = 255;
        }
    // Each cluster is measured over its own box, not the frame: a room leaves dozens of them.
    for (Cluster& c : out) {
        const cv::Rect box = cv::boundingRect(c.mask);
        if (box.empty()) continue;
        const cv::Moments m = cv::moments(c.mask(box), true);
        c.area_px = static_cast<int>(m.m00);
        c.centroid_px = {static_cast<float>(box.x + m.m10 / m.m00),
                         static_cast<float>(box.y + m.m01 / m.m00)};
        std::vector<std::uint16_t> depths;
        for (int y = box.y; y < box.y + box.height; ++y)
            for (int x = box.x; x < box.x + box.width; ++x)
                if (c.mask(y, x)) depths.push_back(depth_mm(y, x));
        std::nth_element(depths.begin(), depths.begin() + depths.size() / 2, depths.end());
        c.medianDepth_m = depths[depths.size() / 2] / kMillimetresPerMetre;
        c.height_m = static_cast<float>(box.height) * c.medianDepth_m / k.fy_px;
    }
    std::erase_if(out, [](const Cluster& c) { return c.area_px == 0; });
    return out;
}

// Whether the mask runs off the top of what the sensor read along more than a few columns
// (one stray pixel there is a leaf's tip, at most).
bool runsOffTop(const cv::Mat1b& mask, const SensedExtent& sensed) {
    constexpr int kMinColumns = 4;
    int columns = 0;
    for (int x = 0; x < mask.cols; ++x) {
        const int top = sensed.firstY[static_cast<std::size_t>(x)];
        for (int y = std::max(0, top - 1); y <= std::min(mask.rows - 1, top + 1); ++y)
            if (mask(y, x)) {
                ++columns;
                break;
            }
    }
    return columns >= kMinColumns;
}

// The objects not taken for the plant's (`joined` 0) and at least `minArea_px` large, largest
// first and at most kMaxLeftOut of them (a room leaves dozens), each outlined, pot and all, with
// its tag.
std::vector<LeftOutObject> leftOutObjects(const std::vector<Cluster>& clusters,
                                          const std::vector<std::string>& tag,
                                          const std::vector<char>& joined, int minArea_px) {
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < clusters.size(); ++i)
        if (!joined[i] && !tag[i].empty() && clusters[i].area_px >= minArea_px) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return clusters[a].area_px > clusters[b].area_px;
    });
    if (order.size() > kMaxLeftOut) order.resize(kMaxLeftOut);
    std::vector<LeftOutObject> out;
    for (const std::size_t i : order) {
        const cv::Mat1b whole = clusters[i].mask | clusters[i].pot;
        const cv::Rect box = cv::boundingRect(whole);
        std::vector<std::vector<cv::Point>> contours;
        cv::findContours(whole(box).clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE,
                         box.tl());
        if (contours.empty()) continue;
        out.push_back({*std::max_element(contours.begin(), contours.end(),
                                         [](const auto& a, const auto& b) {
                                             return cv::contourArea(a) < cv::contourArea(b);
                                         }),
                       tag[i]});
    }
    return out;
}

}  // namespace

FoundPlant findPlant(const cv::Mat1w& depth_mm, const Intrinsics& k, const SegmenterParams& p,
                     StageReport& report) {
    FoundPlant plant;
    cv::Mat1b rest = (depth_mm > 0) & (depth_mm <= p.sceneMaxDepth_m * kMillimetresPerMetre);
    const std::vector<ScenePlane> planes = removeScenePlanes(depth_mm, k, p, rest, report);
    std::vector<Cluster> clusters = euclideanClusters(depth_mm, k, p, rest);
    for (Cluster& c : clusters) {
        int near = 0;
        const cv::Rect box = cv::boundingRect(c.mask);
        for (int y = box.y; y < box.y + box.height; ++y)
            for (int x = box.x; x < box.x + box.width; ++x) {
                if (!c.mask(y, x)) continue;
                const glm::vec3 v = k.backProject(static_cast<float>(x), static_cast<float>(y),
                                                  depth_mm(y, x) / kMillimetresPerMetre);
                const float tolerance_m =
                    kRemnantTolerances * planeTolerance_m(p.scenePlaneDistance_m, v.z);
                for (const ScenePlane& plane : planes)
                    if (planeDistance_m(plane, v) <= tolerance_m) {
                        ++near;
                        break;
                    }
            }
        c.nearPlanes = static_cast<float>(near) / static_cast<float>(std::max(1, c.area_px));
    }
    // A pixel spans 1 / (fx fy) steradians near the optical axis.
    const int minArea_px =
        static_cast<int>(std::min(p.plantMinImageShare * static_cast<float>(depth_mm.total()),
                                  p.plantMinSolidAngle_sr * k.fx_px * k.fy_px));
    std::ostringstream seen;
    seen.precision(2);
    std::vector<std::size_t> thin;
    const SensedExtent sensed = SensedExtent::of(depth_mm);
    int offTop = 0;  // thin and large enough, but running off the top of the view
    // A plant stands on a floor, a table top or the ground, and the guide keeps its base in
    // view. With none in view, what is thin and long is a strip of the room (a curtain's edge
    // against the far wall, a shelf's), or the camera looks where no foot can be found.
    const bool bearingInView = std::any_of(planes.begin(), planes.end(), bearsThings);
    int unborne = 0;  // thin and large enough, but nothing in view to stand on
    // Why the largest object is not a plant, for a user whose plant was not found.
    std::string largestUnlike;
    int largestArea_px = 0;
    std::size_t largestIndex = clusters.size();
    // And the largest object only too small to be one: a plant too far away, most likely, once
    // it covers half the least a plant does.
    std::string largestSmall;
    int largestSmallArea_px = minArea_px / 2;
    std::size_t largestSmallIndex = clusters.size();
    std::vector<std::string> tag(clusters.size());  // why each is not a plant, in a few words
    for (std::size_t i = 0; i < clusters.size(); ++i) {
        Cluster& c = clusters[i];
        // A pot, a box on the floor, a chair's seat: what stands thick on its bottom goes first,
        // so that the parts measured are what grows out of it.
        c.pot = thickBase(c.mask, c.medianDepth_m, k);
        const cv::Mat1b whole = c.mask.clone();
        c.mask &= ~c.pot;
        c.area_px = cv::countNonZero(c.mask);
        if (c.area_px == 0) continue;
        const PartShape shape = partShape(c.mask, c.medianDepth_m, k, true, whole);
        c.meanWidth_m = shape.width_m;
        // What keeps it from being a plant, empty when nothing does.
        std::ostringstream why;
        why.precision(2);
        if (const std::string parts = unlikeLeafParts(shape, p); !parts.empty()) {
            why << "is " << parts;
            tag[i] = shape.width_m > p.plantMaxMeanWidth_m ? "too wide" : "too short for its width";
        } else if (c.nearPlanes > kMaxRemnantShare) {
            why << "lies along the floor or a wall (what their removal left)";
            tag[i] = "floor or wall";
        } else if (c.height_m < p.plantMinHeight_m || c.area_px < minArea_px) {
            tag[i] = "too small";
            why << "is too small (" << c.area_px << " px; a plant: at least " << minArea_px
                << " px and " << p.plantMinHeight_m * 100 << " cm tall)";
            if (c.area_px > largestSmallArea_px) {
                largestSmallArea_px = c.area_px;
                largestSmallIndex = i;
                std::ostringstream small;
                small.precision(2);
                small << "the largest thin one, " << c.height_m << " m tall at " << c.medianDepth_m
                      << " m, " << why.str() << kBringCloser;
                largestSmall = small.str();
            }
        }
        const std::string unlike = why.str();
        if (c.area_px > largestArea_px) {
            largestArea_px = c.area_px;
            largestIndex = i;
            std::ostringstream largest;
            largest.precision(2);
            if (!unlike.empty())
                largest << "the largest, " << c.height_m << " m tall at " << c.medianDepth_m
                        << " m, " << unlike;
            largestUnlike = largest.str();
        }
        if (unlike.empty()) {
            // A plant put before the camera is seen up to its top leaves; what goes on above
            // the view (a door's frame, a curtain, a lamp's pole) is the room's.
            if (runsOffTop(c.mask, sensed)) {
                ++offTop;
                tag[i] = "runs off the top";
                continue;
            }
            if (!bearingInView) {
                ++unborne;
                tag[i] = "nothing to stand on";
                continue;
            }
            thin.push_back(i);
        }
    }
    report.notes.push_back(std::to_string(clusters.size()) + " cluster(s) after " +
                           std::to_string(planes.size()) + " scene plane(s), " +
                           std::to_string(thin.size()) + " thin enough to be a plant");
    if (thin.empty()) {
        std::ostringstream why;
        why.precision(2);
        why << "no plant in view: ";
        if (clusters.empty())
            why << "nothing stands apart from the floor and walls";
        else
            why << clusters.size() << " object(s) stand apart from the floor and walls, none "
                << "large enough and made of parts under " << p.plantMaxMeanWidth_m * 100
                << " cm wide and " << kMinLeafElongation << " times as long, as leaves are";
        if (!largestUnlike.empty()) why << "; " << largestUnlike;
        if (!largestSmall.empty())  // the largest itself, or another
            why << (largestSmallIndex == largestIndex ? std::string(kBringCloser)
                                                      : "; " + largestSmall);
        if (offTop > 0)
            why << "; " << offTop << " that run(s) off the top of the view (a plant too near "
                << "the camera, or a pole or frame of the room)";
        if (unborne > 0)
            why << "; " << unborne
                << " thin enough, but no floor, table top or ground in view (a plant "
                << "stands on one: keep it in view, the camera upright)";
        plant.whyNot = why.str();
        plant.leftOut = leftOutObjects(clusters, tag, std::vector<char>(clusters.size(), 0),
                                       minArea_px / kLeftOutShareOfPlant);
        return plant;
    }
    // The one the camera is aimed at: nearest the image's centre, among those at least a tenth
    // the size of the largest thin one (a stray leaf of the clutter is not the subject).
    int largest = 0;
    for (std::size_t i : thin) largest = std::max(largest, clusters[i].area_px);
    const cv::Point2f centre(0.5f * static_cast<float>(depth_mm.cols),
                             0.5f * static_cast<float>(depth_mm.rows));
    std::size_t chosen = thin.front();
    float best = std::numeric_limits<float>::max();
    for (std::size_t i : thin) {
        if (10 * clusters[i].area_px < largest) continue;
        const float d = static_cast<float>(cv::norm(clusters[i].centroid_px - centre));
        if (d < best) best = d, chosen = i;
    }
    // A plant whose leaves meet only at a stem the sensor hardly reads, or only across depth
    // jumps, falls apart into one cluster a leaf: the thin clusters whose bounds come within
    // the leaf gap at the plant's depth of the plant's join it, in turn; not what stood on
    // something thick (a box's remains) nor slivers of the floor and wall.
    Cluster& c = clusters[chosen];
    // A thick base high above the floor is a broad leaf's, in a piece the plant broke into: no
    // pot, and the piece's own. Each object's is measured once: a room leaves dozens.
    std::vector<char> potStands(clusters.size(), 0);
    for (std::size_t i = 0; i < clusters.size(); ++i)
        potStands[i] = cv::countNonZero(clusters[i].pot) > 0 &&
                       aboveBearing_m(clusters[i].pot, depth_mm, k, planes) <= kPotStandsWithin_m;
    const auto restorePot = [&](std::size_t i) {
        Cluster& o = clusters[i];
        if (potStands[i]) return;
        o.mask |= o.pot;
        o.pot.setTo(0);
    };
    restorePot(chosen);
    std::vector<char> joined(clusters.size(), 0);
    joined[chosen] = 1;
    // A plant stands in one pot. Where the piece aimed at stands in none (a broad leaf before
    // the stem, broken off by the depth jumps around it), a larger thin object beside it that
    // does is the rest of the plant; a smaller one, a box's remains.
    bool standsInPot = potStands[chosen] != 0;
    const float leafGap_m = planeTolerance_m(kLeafGap_m, c.medianDepth_m);
    const int pieceArea_px = c.area_px;
    std::vector<char> isThin(clusters.size(), 0);
    for (const std::size_t i : thin) isThin[i] = 1;
    for (bool grew = true; grew;) {
        grew = false;
        for (std::size_t i = 0; i < clusters.size(); ++i) {
            const Cluster& o = clusters[i];
            const bool plantsPot =
                potStands[i] && !standsInPot && isThin[i] && o.area_px > pieceArea_px;
            if (joined[i] || o.area_px == 0 || o.meanWidth_m > p.plantMaxMeanWidth_m ||
                o.nearPlanes > kMaxJoinedRemnantShare || (potStands[i] && !plantsPot) ||
                !boundsMeet(c, o, leafGap_m))
                continue;
            joined[i] = 1;
            standsInPot = standsInPot || plantsPot;
            restorePot(i);
            grew = true;
            c.mask |= o.mask;
            c.pot |= o.pot;
            for (int a = 0; a < 3; ++a) {
                c.lo[a] = std::min(c.lo[a], o.lo[a]);
                c.hi[a] = std::max(c.hi[a], o.hi[a]);
            }
        }
    }
    c.area_px = cv::countNonZero(c.mask);
    for (const std::size_t i : thin)
        if (!joined[i])
            tag[i] = potStands[i] ? "stands in a pot of its own" : "apart from the plant";
    plant.leftOut = leftOutObjects(clusters, tag, joined, minArea_px / kLeftOutShareOfPlant);
    const cv::Mat1b& pot = c.pot;
    std::ostringstream note;
    note.precision(2);
    note << "plant: " << c.area_px << " px, " << c.height_m << " m tall at " << c.medianDepth_m
         << " m, parts " << c.meanWidth_m * 100 << " cm wide; pot " << cv::countNonZero(pot)
         << " px removed";
    report.notes.push_back(note.str());
    plant.found = true;
    plant.mask = c.mask;
    // Where the plant stands: the top middle of its pot, or else the middle of its lowest row.
    const cv::Mat1b& foot = cv::countNonZero(pot) > 0 ? pot : c.mask;
    const cv::Rect footBox = cv::boundingRect(foot);
    const int footRow = cv::countNonZero(pot) > 0 ? footBox.y : footBox.y + footBox.height - 1;
    std::vector<cv::Point> row;
    cv::findNonZero(foot.row(footRow), row);
    float sum = 0.f;
    for (const cv::Point& q : row) sum += static_cast<float>(q.x);
    plant.base_px = {row.empty() ? footBox.x + 0.5f * footBox.width : sum / row.size(),
                     static_cast<float>(footRow)};
    double nearest = 0, farthest = 0;
    cv::minMaxLoc(depth_mm, &nearest, &farthest, nullptr, nullptr, c.mask);
    plant.near_m = static_cast<float>(nearest) / kMillimetresPerMetre;
    plant.far_m = static_cast<float>(farthest) / kMillimetresPerMetre;
    // Trail candidates: readings of the plant's depth range that no plane and no other cluster
    // holds (a dotted tip falls apart into samples too few to be a cluster of its own).
    plant.candidates = rest & (depth_mm >= nearest) & (depth_mm <= farthest);
    for (std::size_t i = 0; i < clusters.size(); ++i)
        if (!joined[i]) plant.candidates &= ~clusters[i].mask;
    plant.candidates &= ~pot;
    plant.candidates |= plant.mask;
    return plant;
}

}  // namespace meadow::capture::segmentation
