#include "point_splats.h"

#include <pcl/features/normal_3d.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "meadow/synth/error.h"

namespace meadow::synth::plant {

modeling::TriangleMesh splatMesh(const std::vector<glm::vec3>& points, const SplatParams& params) {
    if (points.size() < static_cast<std::size_t>(params.neighbours) + 1)
        throw SynthError("splatMesh: " + std::to_string(points.size()) +
                         " points are too few for splats of " + std::to_string(params.neighbours) +
                         " neighbours");
    auto cloud = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    for (const glm::vec3& p : points) cloud->emplace_back(p.x, p.y, p.z);
    auto tree = pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>();
    pcl::NormalEstimation<pcl::PointXYZ, pcl::Normal> estimation;
    estimation.setInputCloud(cloud);
    estimation.setSearchMethod(tree);
    estimation.setKSearch(params.neighbours);
    pcl::PointCloud<pcl::Normal> normals;
    estimation.compute(normals);

    pcl::KdTreeFLANN<pcl::PointXYZ> neighbours;
    neighbours.setInputCloud(cloud);
    std::vector<int> index(static_cast<std::size_t>(params.neighbours) + 1);
    std::vector<float> d2(index.size());
    std::vector<float> radii(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const int found =
            neighbours.nearestKSearch((*cloud)[i], static_cast<int>(index.size()), index, d2);
        // The farthest of the neighbours: a point beside a gap in the scan reaches across it,
        // which the mean spacing would not (uniformly random points leave gaps of about twice
        // their mean spacing).
        radii[i] = params.radiusScale * std::sqrt(d2[static_cast<std::size_t>(found - 1)]);
    }
    // A stray point far from the rest would become a disc across the whole image.
    std::vector<float> sorted = radii;
    std::nth_element(sorted.begin(),
                     sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    const float largest = params.maxRadiusOverMedian * sorted[sorted.size() / 2];
    modeling::TriangleMesh mesh;
    const int sides = params.sides;
    for (std::size_t i = 0; i < points.size(); ++i) {
        const float radius = std::min(radii[i], largest);
        glm::vec3 n(normals[i].normal_x, normals[i].normal_y, normals[i].normal_z);
        if (!(std::isfinite(n.x) && glm::length(n) > 0.5f)) n = glm::vec3(0.f, 1.f, 0.f);
        n = glm::normalize(n);
        const glm::vec3 helper =
            std::abs(n.x) < 0.9f ? glm::vec3(1.f, 0.f, 0.f) : glm::vec3(0.f, 1.f, 0.f);
        const glm::vec3 u = glm::normalize(glm::cross(n, helper)), v = glm::cross(n, u);
        const auto centre = static_cast<unsigned>(mesh.positions_m.size());
        mesh.positions_m.push_back(points[i]);
        mesh.normals.push_back(n);
        for (int s = 0; s < sides; ++s) {
            const float a = 2.f * std::numbers::pi_v<float> * static_cast<float>(s) / sides;
            mesh.positions_m.push_back(points[i] + radius * (std::cos(a) * u + std::sin(a) * v));
            mesh.normals.push_back(n);
        }
        for (int s = 0; s < sides; ++s)
            mesh.triangles.emplace_back(centre, centre + 1 + static_cast<unsigned>(s),
                                        centre + 1 + static_cast<unsigned>((s + 1) % sides));
    }
    return mesh;
}

}  // namespace meadow::synth::plant
