#pragma once
// Test oracles against the simulated sensor's truth: where a camera ray through a pixel first
// meets a triangle mesh (camera space), by brute force over every triangle (Möller & Trumbore
// 1997, "Fast, minimum storage ray-triangle intersection"), and which pixels of a label image
// lie away from any silhouette.
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <opencv2/core/mat.hpp>

#include "meadow/capture/intrinsics.h"
#include "meadow/modeling/blade_mesh.h"

namespace meadow::test {

struct RayHit {
    float depth_m = std::numeric_limits<float>::infinity();  // camera z; +inf when missed
    float incidence_rad = 0.f;  // between the ray and the hit triangle's normal
};

inline RayHit rayHit(const modeling::TriangleMesh& mesh, const capture::Intrinsics& k, int u,
                     int v) {
    const glm::vec3 d = k.backProject(static_cast<float>(u), static_cast<float>(v), 1.f);
    RayHit best;
    for (const glm::uvec3& tri : mesh.triangles) {
        const glm::vec3 a = mesh.positions_m[tri.x];
        const glm::vec3 e1 = mesh.positions_m[tri.y] - a, e2 = mesh.positions_m[tri.z] - a;
        const glm::vec3 p = glm::cross(d, e2);
        const float det = glm::dot(e1, p);
        if (std::abs(det) < 1e-12f) continue;
        const float inv = 1.f / det;
        const float bu = glm::dot(-a, p) * inv;
        if (bu < 0.f || bu > 1.f) continue;
        const glm::vec3 q = glm::cross(-a, e1);
        const float bv = glm::dot(d, q) * inv;
        if (bv < 0.f || bu + bv > 1.f) continue;
        const float t = glm::dot(e2, q) * inv;  // d has z = 1, so t is the depth
        if (t > 0.f && t < best.depth_m) {
            const glm::vec3 n = glm::normalize(glm::cross(e1, e2));
            best.depth_m = t;
            best.incidence_rad = std::acos(std::min(1.f, std::abs(glm::dot(n, glm::normalize(d)))));
        }
    }
    return best;
}

// Depth (camera z, m) where the ray through pixel (u, v) first meets the mesh, or +inf.
inline float rayDepth_m(const modeling::TriangleMesh& mesh, const capture::Intrinsics& k, int u,
                        int v) {
    return rayHit(mesh, k, u, v).depth_m;
}

// Every pixel of the (2 radius + 1)^2 window around (u, v) carries the label of (u, v): no
// silhouette within `radius` (radius 0: always true inside the image).
inline bool interior(const cv::Mat1w& labels, int u, int v, int radius) {
    if (u < radius || v < radius || u >= labels.cols - radius || v >= labels.rows - radius)
        return false;
    for (int dv = -radius; dv <= radius; ++dv)
        for (int du = -radius; du <= radius; ++du)
            if (labels(v + dv, u + du) != labels(v, u)) return false;
    return true;
}

}  // namespace meadow::test
