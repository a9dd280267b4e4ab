#include "meadow/modeling/blade_mesh.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>
#include <string>

namespace meadow::modeling {

namespace {

// Below this |T x Z| the tangent points along the face normal and T x Z has no direction; the
// previous ring's width direction is carried on instead.
constexpr float kParallelTolerance = 1e-4f;
// Triangles with less area than this (m^2) are slivers at a zero-width end, left out.
constexpr float kMinTriangleArea_m2 = 1e-14f;

// Rodrigues' rotation of v about the unit axis k by angle (rad).
glm::vec3 rotateAbout(const glm::vec3& v, const glm::vec3& k, float angle_rad) {
    const float c = std::cos(angle_rad), s = std::sin(angle_rad);
    return v * c + glm::cross(k, v) * s + k * glm::dot(k, v) * (1.f - c);
}

}  // namespace

float TriangleMesh::surfaceArea_m2() const {
    double area = 0.0;
    for (const glm::uvec3& tri : triangles) {
        const glm::dvec3 a = positions_m[tri.x], b = positions_m[tri.y], c = positions_m[tri.z];
        area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    return static_cast<float>(area);
}

TriangleMesh bladeMesh(const Archetype& archetype, const BladeMeshOptions& options) {
    if (options.segments < 1)
        throw std::invalid_argument("bladeMesh: segments must be >= 1, got " +
                                    std::to_string(options.segments));
    const float left = archetype.leftWidthFraction;
    if (!(left >= 0.f && left <= 1.f))
        throw std::invalid_argument("bladeMesh: leftWidthFraction of '" + archetype.name +
                                    "' must be in [0, 1], got " + std::to_string(left));
    const QuadraticBezier& spine = archetype.spine_m;
    if (!(spine.length() > 0.f))
        throw std::invalid_argument("bladeMesh: archetype '" + archetype.name +
                                    "' has a spine of zero length");

    const int rings = options.segments + 1;
    TriangleMesh mesh;
    mesh.positions_m.reserve(2 * static_cast<std::size_t>(rings));
    mesh.normals.reserve(2 * static_cast<std::size_t>(rings));
    mesh.triangles.reserve(2 * static_cast<std::size_t>(options.segments));

    const glm::vec3 faceNormal{0.f, 0.f, 1.f};
    glm::vec3 previousW{1.f, 0.f, 0.f};
    for (int i = 0; i < rings; ++i) {
        const float s = static_cast<float>(i) / static_cast<float>(options.segments);
        const float t = spine.parameterAtLengthFraction(s);
        const glm::vec3 p = spine.at(t);
        const glm::vec3 T = glm::normalize(spine.tangent(t));
        const glm::vec3 txz = glm::cross(T, faceNormal);
        glm::vec3 W = glm::length(txz) > kParallelTolerance
                          ? glm::normalize(txz)
                          : glm::normalize(previousW - T * glm::dot(previousW, T));
        previousW = W;
        if (archetype.twistAtTip_rad != 0.f) W = rotateAbout(W, T, archetype.twistAtTip_rad * s);
        const glm::vec3 N = glm::normalize(glm::cross(W, T));
        const float w = archetype.width.at(s);
        mesh.positions_m.push_back(p - W * (left * w));
        mesh.positions_m.push_back(p + W * ((1.f - left) * w));
        mesh.normals.push_back(N);
        mesh.normals.push_back(N);
    }

    const auto addIfNotDegenerate = [&mesh](unsigned a, unsigned b, unsigned c) {
        const glm::vec3 &pa = mesh.positions_m[a], &pb = mesh.positions_m[b],
                        &pc = mesh.positions_m[c];
        if (0.5f * glm::length(glm::cross(pb - pa, pc - pa)) > kMinTriangleArea_m2)
            mesh.triangles.emplace_back(a, b, c);
    };
    for (int i = 0; i < options.segments; ++i) {
        const unsigned l0 = 2u * static_cast<unsigned>(i), r0 = l0 + 1, l1 = l0 + 2, r1 = l0 + 3;
        addIfNotDegenerate(l0, r0, r1);
        addIfNotDegenerate(l0, r1, l1);
    }
    return mesh;
}

TriangleMesh transformed(const TriangleMesh& mesh, const glm::mat4& targetFromSource) {
    TriangleMesh out;
    out.triangles = mesh.triangles;
    out.positions_m.reserve(mesh.positions_m.size());
    out.normals.reserve(mesh.normals.size());
    const glm::mat3 rotation(targetFromSource);
    for (const glm::vec3& p : mesh.positions_m)
        out.positions_m.push_back(glm::vec3(targetFromSource * glm::vec4(p, 1.f)));
    for (const glm::vec3& n : mesh.normals) out.normals.push_back(glm::normalize(rotation * n));
    return out;
}

}  // namespace meadow::modeling
