#include "sphere_packing.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <limits>

#include "meadow/runtime/error.h"

namespace meadow::runtime {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr glm::vec2 kRayNudge{0.0123f, 0.0371f};
// A sphere reaching this many voxels past its voxel's depth grew from a voxel outside the mesh.
constexpr float kMisclassified_voxels = 2.f;

struct Grid {
    glm::ivec3 size{0};
    glm::vec3 origin_m{0.f};  // centre of voxel (0, 0, 0)
    float voxel_m = 0.f;
    [[nodiscard]] std::size_t index(int x, int y, int z) const {
        return (static_cast<std::size_t>(z) * size.y + y) * size.x + x;
    }
    [[nodiscard]] glm::vec3 centre(int x, int y, int z) const {
        return origin_m + voxel_m * glm::vec3(x, y, z);
    }
    [[nodiscard]] std::size_t count() const {
        return static_cast<std::size_t>(size.x) * size.y * size.z;
    }
};

// Where the line through (y, z) along +X crosses each triangle (x, sorted): a voxel centre is
// inside when an odd number of crossings lie before it. Triangles met edge-on count once by the
// half-open barycentric test.
std::vector<float> crossingsAlongX(const TriangleMesh& mesh, float y, float z) {
    std::vector<float> xs;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 a = mesh.positions_m[t.x], b = mesh.positions_m[t.y],
                        c = mesh.positions_m[t.z];
        // Barycentric coordinates of (y, z) in the triangle projected onto the YZ plane.
        const float d = (b.y - a.y) * (c.z - a.z) - (c.y - a.y) * (b.z - a.z);
        if (std::abs(d) < 1e-12f) continue;
        const float u = ((y - a.y) * (c.z - a.z) - (c.y - a.y) * (z - a.z)) / d;
        const float v = ((b.y - a.y) * (z - a.z) - (y - a.y) * (b.z - a.z)) / d;
        if (u < 0.f || v < 0.f || u + v >= 1.f) continue;
        xs.push_back(a.x + u * (b.x - a.x) + v * (c.x - a.x));
    }
    std::sort(xs.begin(), xs.end());
    return xs;
}

// Felzenszwalb & Huttenlocher 2012, "Distance Transforms of Sampled Functions", Sec. 3: the lower
// envelope of parabolas rooted at f(q), squared distances along one line of the grid.
void distanceTransform1d(std::vector<float>& f) {
    const int n = static_cast<int>(f.size());
    std::vector<float> d(f.size()), z(f.size() + 1);
    std::vector<int> v(f.size());
    int k = 0;
    int first = 0;
    while (first < n && f[first] == kInfinity) ++first;
    if (first == n) return;  // nothing finite on this line
    v[0] = first;
    z[0] = -kInfinity;
    z[1] = kInfinity;
    for (int q = first + 1; q < n; ++q) {
        if (f[q] == kInfinity) continue;
        float s;
        while (true) {
            const int p = v[k];
            s = ((f[q] + q * q) - (f[p] + p * p)) / (2.f * (q - p));
            if (s > z[k] || k == 0) break;
            --k;
        }
        if (s <= z[k]) {  // k == 0 and the new parabola is below everywhere
            v[0] = q;
            z[1] = kInfinity;
            continue;
        }
        ++k;
        v[k] = q;
        z[k] = s;
        z[k + 1] = kInfinity;
    }
    k = 0;
    for (int q = 0; q < n; ++q) {
        while (z[k + 1] < static_cast<float>(q)) ++k;
        const float dq = static_cast<float>(q - v[k]);
        d[q] = dq * dq + f[v[k]];
    }
    f = d;
}

// Closest point on triangle abc to p (Ericson, "Real-Time Collision Detection", 2005, Sec. 5.1.5).
glm::vec3 closestPointOnTriangle(glm::vec3 p, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0.f && d2 <= 0.f) return a;
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0.f && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.f && d1 >= 0.f && d3 <= 0.f) return a + d1 / (d1 - d3) * ab;
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0.f && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.f && d2 >= 0.f && d6 <= 0.f) return a + d2 / (d2 - d6) * ac;
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0.f && (d4 - d3) >= 0.f && (d5 - d6) >= 0.f)
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    const float denom = 1.f / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

struct SurfacePoint {
    glm::vec3 point{0.f};
    float distance_m = kInfinity;
};

// The mesh's surface point nearest p: its distance is the radius of the largest sphere about an
// inside point.
SurfacePoint nearestSurfacePoint(const TriangleMesh& mesh, glm::vec3 p) {
    SurfacePoint best;
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::vec3 q = closestPointOnTriangle(p, mesh.positions_m[t.x], mesh.positions_m[t.y],
                                                   mesh.positions_m[t.z]);
        if (const float d = glm::distance(p, q); d < best.distance_m) best = {q, d};
    }
    return best;
}

// The largest sphere near `start`: its centre climbs away from the nearest surface point while
// that makes the sphere larger, in steps from half a voxel down to a fiftieth (the grid's centres
// miss the best centre by up to half a voxel along each axis), never further than a voxel.
CollisionSphere largestSphereNear(const TriangleMesh& mesh, glm::vec3 start, float voxel_m) {
    glm::vec3 centre = start;
    SurfacePoint nearest = nearestSurfacePoint(mesh, centre);
    for (float step = 0.5f * voxel_m; step > 0.02f * voxel_m;) {
        const glm::vec3 away = centre - nearest.point;
        if (!(glm::length(away) > 0.f)) break;
        const glm::vec3 next = centre + step * glm::normalize(away);
        if (glm::distance(next, start) > voxel_m) break;  // a refinement, not a search
        const SurfacePoint there = nearestSurfacePoint(mesh, next);
        if (there.distance_m > nearest.distance_m)
            centre = next, nearest = there;
        else
            step *= 0.5f;
    }
    return {centre, nearest.distance_m};
}

}  // namespace

SpherePacking packSpheres(const TriangleMesh& mesh, const SpherePackingParams& params) {
    glm::vec3 lo(kInfinity), hi(-kInfinity);
    for (const glm::vec3& p : mesh.positions_m) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::vec3 extent = hi - lo;
    const float longest = std::max({extent.x, extent.y, extent.z});
    if (mesh.triangles.empty() || !(longest > 0.f))
        throw RuntimeError(mesh.origin + ": a collider mesh needs triangles that enclose a volume");
    Grid g;
    g.voxel_m = longest / static_cast<float>(params.resolution);
    // One empty voxel around the mesh, so the distance to the outside is defined everywhere.
    g.size = glm::ivec3(glm::ceil(extent / g.voxel_m)) + 2;
    g.origin_m =
        lo - 0.5f * g.voxel_m * (glm::vec3(g.size) - extent / g.voxel_m) + 0.5f * g.voxel_m;

    // Inside: crossings parity along +X for each (y, z) row.
    std::vector<char> inside(g.count(), 0);
    std::size_t insideCount = 0;
    for (int z = 0; z < g.size.z; ++z)
        for (int y = 0; y < g.size.y; ++y) {
            // The ray is nudged off the voxel centre by a small odd fraction of a voxel: a grid
            // aligned with the mesh's vertices would send rays through shared edges, counted
            // twice or not at all.
            const glm::vec3 c0 = g.centre(0, y, z);
            const std::vector<float> xs = crossingsAlongX(mesh, c0.y + kRayNudge.x * g.voxel_m,
                                                          c0.z + kRayNudge.y * g.voxel_m);
            std::size_t passed = 0;
            for (int x = 0; x < g.size.x; ++x) {
                const float cx = g.centre(x, y, z).x;
                while (passed < xs.size() && xs[passed] < cx) ++passed;
                if (passed % 2 == 1) inside[g.index(x, y, z)] = 1, ++insideCount;
            }
        }
    if (insideCount == 0)
        throw RuntimeError(mesh.origin + ": the collider mesh encloses no volume at " +
                           std::to_string(params.resolution) +
                           " voxels along its longest side; give a closed mesh");

    // Squared distance (voxels) from each voxel centre to the nearest outside voxel centre.
    std::vector<float> d2(g.count());
    for (std::size_t i = 0; i < d2.size(); ++i) d2[i] = inside[i] ? kInfinity : 0.f;
    auto pass = [&](int axis) {
        const glm::ivec3 s = g.size;
        const int n = s[axis];
        std::vector<float> line(static_cast<std::size_t>(n));
        const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
        for (int i = 0; i < s[a1]; ++i)
            for (int j = 0; j < s[a2]; ++j) {
                glm::ivec3 p;
                p[a1] = i, p[a2] = j;
                for (int k = 0; k < n; ++k) p[axis] = k, line[k] = d2[g.index(p.x, p.y, p.z)];
                distanceTransform1d(line);
                for (int k = 0; k < n; ++k) p[axis] = k, d2[g.index(p.x, p.y, p.z)] = line[k];
            }
    };
    pass(0), pass(1), pass(2);

    // The surface lies half a voxel short of the nearest outside centre.
    auto depth_m = [&](std::size_t i) { return (std::sqrt(d2[i]) - 0.5f) * g.voxel_m; };
    SpherePacking out;
    out.voxel_m = g.voxel_m;
    std::vector<char> covered(g.count(), 0);
    std::size_t coveredCount = 0;
    while (static_cast<int>(out.spheres.size()) < params.maxSpheres &&
           static_cast<float>(coveredCount) < params.coverage * static_cast<float>(insideCount)) {
        std::size_t best = 0;
        float bestDepth = -1.f;
        for (std::size_t i = 0; i < g.count(); ++i)
            if (inside[i] && !covered[i] && depth_m(i) > bestDepth)
                best = i, bestDepth = depth_m(i);
        if (bestDepth < 0.f) break;
        const int x = static_cast<int>(best % g.size.x);
        const int y = static_cast<int>(best / g.size.x % g.size.y);
        const int z = static_cast<int>(best / (static_cast<std::size_t>(g.size.x) * g.size.y));
        // The voxel depth only ranks the candidates (it is half a voxel off either way); the
        // sphere reaches to the surface itself.
        CollisionSphere s = largestSphereNear(mesh, g.centre(x, y, z), g.voxel_m);
        s.radius_m = std::max(s.radius_m, 0.5f * g.voxel_m);
        // A voxel the parity test took for inside by a ray grazing an edge lies outside: its
        // sphere would reach far past its depth. It is set aside, not used.
        if (s.radius_m > bestDepth + kMisclassified_voxels * g.voxel_m) {
            covered[best] = 1, ++coveredCount;
            continue;
        }
        out.spheres.push_back(s);
        for (std::size_t i = 0; i < g.count(); ++i) {
            if (!inside[i] || covered[i]) continue;
            const int xi = static_cast<int>(i % g.size.x);
            const int yi = static_cast<int>(i / g.size.x % g.size.y);
            const int zi = static_cast<int>(i / (static_cast<std::size_t>(g.size.x) * g.size.y));
            // Within half a voxel: the voxel overlaps the sphere (the grid resolves no finer).
            if (glm::distance(g.centre(xi, yi, zi), s.center_m) <= s.radius_m + 0.5f * g.voxel_m)
                covered[i] = 1, ++coveredCount;
        }
    }
    out.coverage = static_cast<float>(coveredCount) / static_cast<float>(insideCount);
    return out;
}

}  // namespace meadow::runtime
