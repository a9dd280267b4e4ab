// Ground and background removal with PCL: fit large planes to the masked points and clear the
// pixels within planeDistance_m of them. Two fitters, selectable:
//  - Ransac: pcl::SACSegmentation with SACMODEL_PERPENDICULAR_PLANE about the camera's vertical
//    axis, so only ground-like planes can win; a tuft seen from the side is itself nearly a plane
//    and must never be removed, and the back wall is the depth band's job.
//  - OrganizedMultiPlane: integral-image normals + pcl::OrganizedMultiPlaneSegmentation, then
//    the same tilt test on each plane found.
// Both fit on a strided sample and then test every masked pixel against the plane equation,
// which is cheaper than fitting on all pixels and gives the same inliers.
// This is one of the two files that include PCL (the other is outlier_removal.cpp).
#include <pcl/ModelCoefficients.h>
#include <pcl/features/integral_image_normal.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/sample_consensus/method_types.h>
#include <pcl/sample_consensus/model_types.h>
#include <pcl/segmentation/organized_multi_plane_segmentation.h>
#include <pcl/segmentation/sac_segmentation.h>

#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "segmentation/stages.h"

namespace meadow::capture::segmentation {

namespace {

constexpr float kDegToRad = std::numbers::pi_v<float> / 180.0f;
// OrganizedMultiPlaneSegmentation: normals of one plane may differ by this much (PCL default
// is 3 deg; sensor noise at 1-2 m needs more), and neighbouring depths by this factor of depth.
constexpr float kOmpsAngularThreshold_deg = 5.0f;
constexpr float kNormalMaxDepthChangeFactor = 0.02f;
constexpr float kNormalSmoothingSize_px = 10.0f;
constexpr int kRansacSeed = 12345;  // deterministic results run to run
// A ground plane is a solid region: at least this share of its inliers has all 8 neighbours
// inliers too (the noisy, quantised ground of the simulated sensor scores well above it at the
// sample stride; thin blades far below).
constexpr float kMinPlaneSolidity = 0.3f;
// Rejected (non-solid) planes give RANSAC this many more tries to find the ground.
constexpr int kExtraPlaneAttempts = 2;
// Plane inliers are cleared only in connected regions of at least this share of the image
// (0.5 % = 1536 px at 640x480): ground, not the band where a plane crosses a blade.
constexpr float kMinGroundComponentFraction = 0.005f;
constexpr double kSmallGroundMeanDistanceFraction = 0.3;
// Nothing is seen through the ground: a plane with more than kMaxShareBelow of the masked
// points farther than kBelowTolerances plane tolerances beneath it (on the side away from the
// camera) is not the ground. A plane through the tuft's fan, which leans toward the camera and
// passes the tilt and solidity tests, has the back wall and the far blades beneath it; taken
// for the ground it removes the tuft's base and cuts its blades at mid-height.
constexpr float kBelowTolerances = 3.0f;
constexpr double kMaxShareBelow = 0.05;

struct Plane {
    Eigen::Vector4f coefficients;  // n.x + d = 0, |n| = 1
};

float tilt_deg(const Eigen::Vector3f& n) {
    // Angle between the plane's normal and the camera's vertical axis: 0 = level ground seen
    // by a level camera, 90 = a wall facing the camera.
    return std::acos(std::min(1.0f, std::abs(n.y()) / n.norm())) / kDegToRad;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr sampleCloud(const cv::Mat1w& depth_mm, const Intrinsics& K,
                                                const cv::Mat1b& mask, int stride, bool organized) {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    const int w = (depth_mm.cols + stride - 1) / stride, h = (depth_mm.rows + stride - 1) / stride;
    if (organized) {
        cloud->width = static_cast<std::uint32_t>(w);
        cloud->height = static_cast<std::uint32_t>(h);
        cloud->is_dense = false;
        cloud->points.resize(static_cast<size_t>(w) * static_cast<size_t>(h));
    }
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int y = 0, sy = 0; y < depth_mm.rows; y += stride, ++sy)
        for (int x = 0, sx = 0; x < depth_mm.cols; x += stride, ++sx) {
            const auto d = depth_mm(y, x);
            pcl::PointXYZ p(nan, nan, nan);
            if (d != 0 && mask(y, x) != 0) {
                const auto v = K.backProject(static_cast<float>(x), static_cast<float>(y),
                                             static_cast<float>(d) / kMillimetresPerMetre);
                p = pcl::PointXYZ(v.x, v.y, v.z);
            } else if (!organized) {
                continue;
            }
            if (organized)
                (*cloud)(static_cast<std::uint32_t>(sx), static_cast<std::uint32_t>(sy)) = p;
            else
                cloud->push_back(p);
        }
    return cloud;
}

// Share of the masked pixels (on a stride) lying more than `depth_m` beneath the plane, i.e. on
// the side away from the camera.
double shareBelow(const cv::Mat1w& depth_mm, const Intrinsics& K, const Plane& plane, float depth_m,
                  const cv::Mat1b& mask, int stride) {
    Eigen::Vector4f c = plane.coefficients;
    if (c[3] < 0.f) c = -c;  // the camera (origin) on the positive side
    double all = 0, below = 0;
    for (int y = 0; y < depth_mm.rows; y += stride)
        for (int x = 0; x < depth_mm.cols; x += stride) {
            const auto d = depth_mm(y, x);
            if (d == 0 || mask(y, x) == 0) continue;
            const auto v = K.backProject(static_cast<float>(x), static_cast<float>(y),
                                         static_cast<float>(d) / kMillimetresPerMetre);
            all += 1;
            below += c[0] * v.x + c[1] * v.y + c[2] * v.z + c[3] < -depth_m ? 1 : 0;
        }
    return all > 0 ? below / all : 0.0;
}

// Clears the mask pixels within tolerance of the plane that form large connected regions;
// returns how many. Small inlier regions are where the plane merely cuts through blades: a
// ground plane fitted to the thin strip of ground a grazing view still reads is poorly
// constrained and may pass through the tuft, and those crossings must stay.
int clearPlane(const cv::Mat1w& depth_mm, const Intrinsics& K, const Plane& plane,
               float tolerance_m, cv::Mat1b& mask) {
    const Eigen::Vector4f& c = plane.coefficients;
    cv::Mat1b inliers(mask.size(), std::uint8_t{0});
    cv::Mat1f distance_m(mask.size(), 0.f);
    for (int y = 0; y < depth_mm.rows; ++y) {
        const auto* m = mask[y];
        const auto* d = depth_mm[y];
        auto* in = inliers[y];
        for (int x = 0; x < depth_mm.cols; ++x) {
            if (m[x] == 0 || d[x] == 0) continue;
            const auto v = K.backProject(static_cast<float>(x), static_cast<float>(y),
                                         static_cast<float>(d[x]) / kMillimetresPerMetre);
            const float e = std::abs(c[0] * v.x + c[1] * v.y + c[2] * v.z + c[3]);
            if (e <= tolerance_m) {
                in[x] = 255;
                distance_m(y, x) = e;
            }
        }
    }
    cv::Mat1i labels;
    cv::Mat stats, centroids;
    const int n = cv::connectedComponentsWithStats(inliers, labels, stats, centroids, 8, CV_32S);
    const int minArea =
        static_cast<int>(kMinGroundComponentFraction * static_cast<float>(mask.total()));
    // Small regions (ground seen between blades) are cleared only when they lie on the plane:
    // a slab through a blade spreads its distances over the whole tolerance (mean |d| about
    // tolerance / 2), ground reads the plane up to sensor noise.
    std::vector<double> sumDistance(static_cast<size_t>(n), 0.0);
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x)
            sumDistance[static_cast<size_t>(labels(y, x))] += distance_m(y, x);
    std::vector<char> clear(static_cast<size_t>(n), 0);
    for (int i = 1; i < n; ++i) {
        const int area = stats.at<int>(i, cv::CC_STAT_AREA);
        const double meanDistance = sumDistance[static_cast<size_t>(i)] / std::max(1, area);
        clear[static_cast<size_t>(i)] =
            area >= minArea || meanDistance < kSmallGroundMeanDistanceFraction * tolerance_m;
    }
    int cleared = 0;
    for (int y = 0; y < mask.rows; ++y) {
        auto* m = mask[y];
        const auto* l = labels[y];
        for (int x = 0; x < mask.cols; ++x)
            if (clear[static_cast<size_t>(l[x])]) {
                m[x] = 0;
                ++cleared;
            }
    }
    return cleared;
}

// Share of a plane's inliers (on the sample grid) whose 8 neighbours are inliers too. The ground
// or a table top is a solid region; a fan of blades that happens to lie near one plane is a
// set of thin strips and must not be removed as "ground".
float solidity(const cv::Mat1w& depth_mm, const Intrinsics& K, const Plane& plane,
               float tolerance_m, const cv::Mat1b& mask, int stride) {
    const int w = (depth_mm.cols + stride - 1) / stride, h = (depth_mm.rows + stride - 1) / stride;
    cv::Mat1b inliers(h, w, std::uint8_t{0});
    const Eigen::Vector4f& c = plane.coefficients;
    for (int y = 0, sy = 0; y < depth_mm.rows; y += stride, ++sy)
        for (int x = 0, sx = 0; x < depth_mm.cols; x += stride, ++sx) {
            const auto d = depth_mm(y, x);
            if (d == 0 || mask(y, x) == 0) continue;
            const auto v = K.backProject(static_cast<float>(x), static_cast<float>(y),
                                         static_cast<float>(d) / kMillimetresPerMetre);
            if (std::abs(c[0] * v.x + c[1] * v.y + c[2] * v.z + c[3]) <= tolerance_m)
                inliers(sy, sx) = 255;
        }
    const int all = cv::countNonZero(inliers);
    if (all == 0) return 0.f;
    // Closing first: single missing readings (dropouts) must not make the ground look porous.
    cv::Mat1b interior;
    cv::morphologyEx(inliers, interior, cv::MORPH_CLOSE, cv::Mat());
    cv::erode(interior, interior, cv::Mat());
    interior &= inliers;
    return static_cast<float>(cv::countNonZero(interior)) / static_cast<float>(all);
}

std::vector<Plane> ransacPlanes(const cv::Mat1w& depth_mm, const Intrinsics& K,
                                const SegmenterParams& params, cv::Mat1b mask,
                                std::vector<std::string>& notes) {
    std::vector<Plane> planes;
    const int stride = params.planeSampleStride_px;
    cv::Mat1b candidates = mask.clone();  // rejected planes leave the candidates, not the mask
    const int maxAttempts = params.maxPlanes + kExtraPlaneAttempts;
    for (int attempt = 0;
         attempt < maxAttempts && static_cast<int>(planes.size()) < params.maxPlanes; ++attempt) {
        auto cloud = sampleCloud(depth_mm, K, candidates, stride, /*organized=*/false);
        const auto minInliers =
            static_cast<size_t>(params.minPlaneFraction * static_cast<float>(cloud->size()));
        if (cloud->size() < 3) break;
        pcl::SACSegmentation<pcl::PointXYZ> sac;
        sac.setOptimizeCoefficients(true);
        sac.setModelType(pcl::SACMODEL_PERPENDICULAR_PLANE);
        sac.setAxis(Eigen::Vector3f(0.f, 1.f, 0.f));
        sac.setEpsAngle(params.maxGroundTilt_deg * kDegToRad);
        sac.setMethodType(pcl::SAC_RANSAC);
        sac.setDistanceThreshold(params.planeDistance_m);
        sac.setMaxIterations(params.ransacIterations);
        sac.setInputCloud(cloud);
        pcl::PointIndices inliers;
        pcl::ModelCoefficients coefficients;
        srand(kRansacSeed);  // PCL's RANSAC draws samples with rand()
        sac.segment(inliers, coefficients);
        if (coefficients.values.size() != 4 ||
            inliers.indices.size() < std::max<size_t>(3, minInliers)) {
            if (planes.empty())
                notes.push_back("no oblique plane holds " +
                                std::to_string(static_cast<int>(100 * params.minPlaneFraction)) +
                                " % of the masked points");
            break;
        }
        Plane plane;
        plane.coefficients = Eigen::Vector4f(coefficients.values[0], coefficients.values[1],
                                             coefficients.values[2], coefficients.values[3]);
        plane.coefficients /= plane.coefficients.head<3>().norm();
        if (tilt_deg(plane.coefficients.head<3>()) > params.maxGroundTilt_deg) break;
        if (const double below = shareBelow(
                depth_mm, K, plane, kBelowTolerances * params.planeDistance_m, mask, stride);
            below > kMaxShareBelow) {
            notes.push_back("kept a plane of " + std::to_string(inliers.indices.size()) +
                            " samples: " + std::to_string(static_cast<int>(100 * below)) +
                            " % of the points lie beneath it, so it is not the ground");
            clearPlane(depth_mm, K, plane, params.planeDistance_m, candidates);
            continue;
        }
        const float solid =
            solidity(depth_mm, K, plane, params.planeDistance_m, candidates, stride);
        if (solid < kMinPlaneSolidity) {
            std::ostringstream s;
            s.precision(2);
            s << "kept a plane of " << inliers.indices.size() << " samples: only " << solid
              << " of its inliers are interior (thin strips, e.g. blades), not ground";
            notes.push_back(s.str());
            clearPlane(depth_mm, K, plane, params.planeDistance_m, candidates);
            continue;
        }
        planes.push_back(plane);
        clearPlane(depth_mm, K, plane, params.planeDistance_m, candidates);
    }
    return planes;
}

std::vector<Plane> organizedPlanes(const cv::Mat1w& depth_mm, const Intrinsics& K,
                                   const SegmenterParams& params, const cv::Mat1b& mask,
                                   std::vector<std::string>& notes) {
    auto cloud = sampleCloud(depth_mm, K, mask, params.planeSampleStride_px, /*organized=*/true);
    size_t valid = 0;
    for (const auto& p : cloud->points) valid += std::isfinite(p.z) ? 1 : 0;
    if (valid < 3) return {};
    auto normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
    pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> ne;
    ne.setNormalEstimationMethod(ne.AVERAGE_3D_GRADIENT);
    ne.setMaxDepthChangeFactor(kNormalMaxDepthChangeFactor);
    ne.setNormalSmoothingSize(kNormalSmoothingSize_px /
                              static_cast<float>(params.planeSampleStride_px));
    ne.setInputCloud(cloud);
    ne.compute(*normals);

    pcl::OrganizedMultiPlaneSegmentation<pcl::PointXYZ, pcl::Normal, pcl::Label> mps;
    mps.setMinInliers(static_cast<unsigned>(std::max<size_t>(
        3, static_cast<size_t>(params.minPlaneFraction * static_cast<float>(valid)))));
    mps.setAngularThreshold(kOmpsAngularThreshold_deg * kDegToRad);
    mps.setDistanceThreshold(params.planeDistance_m);
    mps.setInputNormals(normals);
    mps.setInputCloud(cloud);
    std::vector<pcl::PlanarRegion<pcl::PointXYZ>,
                Eigen::aligned_allocator<pcl::PlanarRegion<pcl::PointXYZ>>>
        regions;
    mps.segment(regions);
    std::vector<std::pair<size_t, Plane>> found;
    for (const auto& r : regions) {
        Plane plane;
        plane.coefficients = r.getCoefficients();
        plane.coefficients /= plane.coefficients.head<3>().norm();
        if (tilt_deg(plane.coefficients.head<3>()) > params.maxGroundTilt_deg) {
            notes.push_back("kept a plane tilted beyond maxGroundTilt_deg (" +
                            std::to_string(r.getCount()) + " samples): not ground");
            continue;
        }
        if (const double below =
                shareBelow(depth_mm, K, plane, kBelowTolerances * params.planeDistance_m, mask,
                           params.planeSampleStride_px);
            below > kMaxShareBelow) {
            notes.push_back("kept a plane of " + std::to_string(r.getCount()) +
                            " samples: " + std::to_string(static_cast<int>(100 * below)) +
                            " % of the points lie beneath it, so it is not the ground");
            continue;
        }
        if (solidity(depth_mm, K, plane, params.planeDistance_m, mask,
                     params.planeSampleStride_px) < kMinPlaneSolidity) {
            notes.push_back("kept a plane of " + std::to_string(r.getCount()) +
                            " samples: its inliers are thin strips (blades), not ground");
            continue;
        }
        found.emplace_back(r.getCount(), plane);
    }
    std::sort(found.begin(), found.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<Plane> planes;
    for (size_t i = 0; i < found.size() && static_cast<int>(i) < params.maxPlanes; ++i)
        planes.push_back(found[i].second);
    if (planes.empty())
        notes.push_back("no oblique plane holds " +
                        std::to_string(static_cast<int>(100 * params.minPlaneFraction)) +
                        " % of the masked points");
    return planes;
}

}  // namespace

std::optional<cv::Vec4f> removePlanes(const cv::Mat1w& depth_mm, const Intrinsics& intrinsics,
                                      const SegmenterParams& params, cv::Mat1b& mask,
                                      StageReport& report) {
    if (cv::countNonZero(mask) < 3) return std::nullopt;
    const auto planes = params.planeMethod == PlaneMethod::Ransac
                            ? ransacPlanes(depth_mm, intrinsics, params, mask.clone(), report.notes)
                            : organizedPlanes(depth_mm, intrinsics, params, mask, report.notes);
    for (const auto& plane : planes) {
        const int cleared = clearPlane(depth_mm, intrinsics, plane, params.planeDistance_m, mask);
        const auto& c = plane.coefficients;
        std::ostringstream s;
        s.precision(3);
        s << toString(params.planeMethod) << " plane n=(" << c[0] << ", " << c[1] << ", " << c[2]
          << ") d=" << c[3] << " m, tilted " << tilt_deg(c.head<3>())
          << " deg from level: " << cleared << " px dropped as ground/background";
        report.notes.push_back(s.str());
    }
    if (planes.empty()) return std::nullopt;
    // The normal points up, away from the ground: toward the camera's -y (y is down).
    Eigen::Vector4f c = planes.front().coefficients;
    if (c[1] > 0.f) c = -c;
    return cv::Vec4f(c[0], c[1], c[2], c[3]);
}

}  // namespace meadow::capture::segmentation
