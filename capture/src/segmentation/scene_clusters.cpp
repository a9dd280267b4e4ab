#include "segmentation/scene_clusters.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/organized.h>
#include <pcl/segmentation/extract_clusters.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "segmentation/scene_planes.h"

namespace meadow::capture::segmentation::scene {

namespace {

constexpr int kClusterStride_px = 2;  // clusters are found on every 2nd pixel of every 2nd row
// A depth jump spans this many of the sensor's 90th-percentile neighbour steps, at least.
constexpr float kJumpSteps = 2.f;

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

}  // namespace

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
        (*cloud)[static_cast<std::size_t>(at)] = {s[i].p.x, s[i].p.y, s[i].p.z};
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
            const glm::vec3& q = s[static_cast<std::size_t>(i)].p;
            for (int a = 0; a < 3; ++a) {
                out[c].lo[a] = std::min(out[c].lo[a], q[a]);
                out[c].hi[a] = std::max(out[c].hi[a], q[a]);
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

}  // namespace meadow::capture::segmentation::scene
