#include "rasteriser.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

namespace meadow::synth::detail {
namespace {

// Triangles are clipped at this depth in front of the viewer: 1/z stays finite and screen
// coordinates stay within what double edge functions resolve. Far below any sensor's range.
constexpr double kNearClip_m = 1e-3;
// Screen-space area (px^2) under which a triangle is treated as degenerate (seen edge-on):
// it covers no pixel centre reliably and its barycentrics would divide by ~0.
constexpr double kMinScreenArea_px2 = 1e-12;

struct ScreenVertex {
    glm::dvec2 s_px;   // image position
    double invZ = 0.;  // 1/z: affine in screen space, so interpolating it is perspective-correct
};

// Edge function (twice the signed area of a, b, p), evaluated with the endpoints in a canonical
// order so that the edge shared by two triangles gives exactly opposite values for both: a
// pixel centre on a shared edge is then covered by at least one of them, never by neither.
struct Edge {
    glm::dvec2 origin;
    glm::dvec2 direction;
    double sign = 1.0;

    Edge(const glm::dvec2& a, const glm::dvec2& b) {
        const bool aFirst = a.x < b.x || (a.x == b.x && a.y < b.y);
        origin = aFirst ? a : b;
        direction = (aFirst ? b : a) - origin;
        sign = aFirst ? 1.0 : -1.0;
    }
    [[nodiscard]] double operator()(const glm::dvec2& p) const {
        return sign * (direction.x * (p.y - origin.y) - direction.y * (p.x - origin.x));
    }
};

struct Target {
    const Intrinsics& k;
    RasterImage& image;
    bool withAttributes;
};

void rasteriseScreenTriangle(const std::array<ScreenVertex, 3>& v, std::uint16_t label,
                             const cv::Vec3f& normal, Target& target) {
    const Edge e0{v[1].s_px, v[2].s_px};
    const Edge e1{v[2].s_px, v[0].s_px};
    const Edge e2{v[0].s_px, v[1].s_px};
    const double area = e2(v[2].s_px);
    if (std::abs(area) < kMinScreenArea_px2) return;
    const double minX = std::min({v[0].s_px.x, v[1].s_px.x, v[2].s_px.x});
    const double maxX = std::max({v[0].s_px.x, v[1].s_px.x, v[2].s_px.x});
    const double minY = std::min({v[0].s_px.y, v[1].s_px.y, v[2].s_px.y});
    const double maxY = std::max({v[0].s_px.y, v[1].s_px.y, v[2].s_px.y});
    if (maxX < 0.0 || maxY < 0.0 || minX > target.k.width_px - 1.0 ||
        minY > target.k.height_px - 1.0)
        return;
    // Clamp in double before converting: a vertex close to the near plane can project far
    // outside the image, beyond what an int holds.
    const int x0 = static_cast<int>(std::ceil(std::clamp(minX, 0.0, target.k.width_px - 1.0)));
    const int x1 = static_cast<int>(std::floor(std::clamp(maxX, 0.0, target.k.width_px - 1.0)));
    const int y0 = static_cast<int>(std::ceil(std::clamp(minY, 0.0, target.k.height_px - 1.0)));
    const int y1 = static_cast<int>(std::floor(std::clamp(maxY, 0.0, target.k.height_px - 1.0)));
    const double sign = area > 0.0 ? 1.0 : -1.0;
    const double invArea = 1.0 / area;
    for (int y = y0; y <= y1; ++y) {
        float* depthRow = target.image.depth_m.ptr<float>(y);
        for (int x = x0; x <= x1; ++x) {
            const glm::dvec2 p{x, y};
            const double w0 = e0(p);
            const double w1 = e1(p);
            const double w2 = e2(p);
            if (sign * w0 < 0.0 || sign * w1 < 0.0 || sign * w2 < 0.0) continue;
            const double invZ = (w0 * v[0].invZ + w1 * v[1].invZ + w2 * v[2].invZ) * invArea;
            if (!(invZ > 0.0)) continue;
            const auto z_m = static_cast<float>(1.0 / invZ);
            float& stored = depthRow[x];
            if (stored != 0.f && stored <= z_m) continue;  // ties keep the earlier mesh
            stored = z_m;
            if (target.withAttributes) {
                target.image.labels(y, x) = label;
                target.image.normals(y, x) = normal;
            }
        }
    }
}

ScreenVertex toScreen(const glm::dvec3& p_m, const Intrinsics& k) {
    const double invZ = 1.0 / p_m.z;
    return {{k.fx_px * p_m.x * invZ + k.cx_px, k.fy_px * p_m.y * invZ + k.cy_px}, invZ};
}

// Sutherland-Hodgman against z >= kNearClip_m: a triangle becomes 0, 3 or 4 vertices.
int clipNear(const std::array<glm::dvec3, 3>& in, std::array<glm::dvec3, 4>& out) {
    int n = 0;
    for (int i = 0; i < 3; ++i) {
        const glm::dvec3& a = in[i];
        const glm::dvec3& b = in[(i + 1) % 3];
        const bool aIn = a.z >= kNearClip_m;
        const bool bIn = b.z >= kNearClip_m;
        if (aIn) out[n++] = a;
        if (aIn != bIn) {
            const double t = (kNearClip_m - a.z) / (b.z - a.z);
            glm::dvec3 c = a + t * (b - a);
            c.z = kNearClip_m;  // exactly on the plane, whatever the rounding of t
            out[n++] = c;
        }
    }
    return n;
}

}  // namespace

std::string meshProblem(const LabelledMesh& mesh, std::size_t meshIndex) {
    const std::string name =
        "mesh " + std::to_string(meshIndex) + " (label " + std::to_string(mesh.label) + ")";
    for (std::size_t i = 0; i < mesh.positions_m.size(); ++i) {
        const glm::vec3& p = mesh.positions_m[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return name + ": vertex " + std::to_string(i) + " is not finite";
    }
    const std::size_t count = mesh.positions_m.size();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const glm::uvec3& tri = mesh.triangles[t];
        for (int c = 0; c < 3; ++c)
            if (tri[c] >= count)
                return name + ": triangle " + std::to_string(t) + " uses vertex " +
                       std::to_string(tri[c]) + " but the mesh has " + std::to_string(count);
    }
    return {};
}

RasterImage rasterise(const std::vector<LabelledMesh>& meshes, const Intrinsics& intrinsics,
                      const glm::vec3& viewerOrigin_m, bool withAttributes) {
    RasterImage image;
    image.depth_m = cv::Mat1f::zeros(intrinsics.height_px, intrinsics.width_px);
    if (withAttributes) {
        image.labels = cv::Mat1w::zeros(intrinsics.height_px, intrinsics.width_px);
        image.normals = cv::Mat3f::zeros(intrinsics.height_px, intrinsics.width_px);
    }
    Target target{intrinsics, image, withAttributes};
    const glm::dvec3 origin{viewerOrigin_m};
    for (const LabelledMesh& mesh : meshes) {
        for (const glm::uvec3& tri : mesh.triangles) {
            const std::array<glm::dvec3, 3> p{glm::dvec3{mesh.positions_m[tri.x]} - origin,
                                              glm::dvec3{mesh.positions_m[tri.y]} - origin,
                                              glm::dvec3{mesh.positions_m[tri.z]} - origin};
            // Face normal before clipping (clipping keeps the plane); turned to face the
            // viewer because blades are two-sided and the incidence angle is unsigned.
            glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
            const double length = glm::length(n);
            if (!(length > 0.0)) continue;  // degenerate in 3D: no surface to see
            n /= length;
            if (glm::dot(n, p[0]) > 0.0) n = -n;
            const cv::Vec3f normal{static_cast<float>(n.x), static_cast<float>(n.y),
                                   static_cast<float>(n.z)};

            std::array<glm::dvec3, 4> clipped;
            const int count = clipNear(p, clipped);
            if (count < 3) continue;
            const ScreenVertex s0 = toScreen(clipped[0], intrinsics);
            for (int i = 1; i + 1 < count; ++i)  // fan: 1 or 2 triangles
                rasteriseScreenTriangle(
                    {s0, toScreen(clipped[i], intrinsics), toScreen(clipped[i + 1], intrinsics)},
                    mesh.label, normal, target);
        }
    }
    return image;
}

}  // namespace meadow::synth::detail
