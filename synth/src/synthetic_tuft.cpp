// Synthetic tuft geometry: camera pose, scenery, blade placement, curl and wind.
#include "meadow/synth/synthetic_tuft.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace meadow::synth {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
// Ground and wall reach this far to each side (m): wider than the widest view at 1.6 m depth.
constexpr float kSceneryHalfWidth_m = 3.f;
constexpr float kWallHeight_m = 3.f;
// The ground stops this far in front of the camera (m along world Z) so no vertex lies behind
// the image plane, where a pinhole projection is undefined.
constexpr float kGroundNearGap_m = 0.25f;
// Wind may shorten the chord (base to tip) to at most this fraction of the blade's length: a
// straight chord would leave no room for v1 and no curve of the same length.
constexpr float kMaxChordFraction = 0.97f;
// Turbulence on top of the gust: its frequency relative to the gust, and its share.
constexpr float kTurbulenceFrequencyRatio = 2.7f;
constexpr float kTurbulenceShare = 0.2f;
// Bisection steps for v1: 60 halvings of [0, 2 L] reach far below float resolution.
constexpr int kLengthBisectionSteps = 60;

synth::LabelledMesh quad(const glm::mat4& cameraFromWorld, const glm::vec3& a, const glm::vec3& b,
                         const glm::vec3& c, const glm::vec3& d) {
    synth::LabelledMesh mesh;
    for (const glm::vec3& p : {a, b, c, d})
        mesh.positions_m.push_back(glm::vec3(cameraFromWorld * glm::vec4(p, 1.f)));
    mesh.triangles = {{0u, 1u, 2u}, {0u, 2u, 3u}};
    mesh.label = 0;
    return mesh;
}

// Rotation part of worldFromBlade (see synthetic_tuft.h).
glm::mat4 bladeRotation(const BladePlacement& b) {
    glm::mat4 r = glm::rotate(glm::mat4(1.f), -b.lean_rad, glm::vec3(0.f, 0.f, 1.f));
    r = glm::rotate(r, b.yaw_rad, glm::vec3(0.f, 1.f, 0.f));
    if (!b.bendsTowardPlusX) r = glm::rotate(r, kPi, glm::vec3(0.f, 1.f, 0.f));
    return r;
}

glm::vec3 restBaseDirection(const QuadraticBezier& spine) {
    const glm::vec3 d = spine.v1 - spine.v0;
    const float n = glm::length(d);
    return n > 0.f ? d / n : glm::vec3(0.f, 1.f, 0.f);
}

}  // namespace

glm::mat4 TuftCamera::cameraFromWorld() const {
    // Camera centre on the sphere around the target, raised by the tilt; OpenCV axes:
    // z forward (toward the target), x right (world +X when level), y down.
    const glm::vec3 centre =
        target_m + distance_m * glm::vec3(0.f, std::sin(tilt_rad), std::cos(tilt_rad));
    const glm::vec3 z = glm::normalize(target_m - centre);
    const glm::vec3 x = glm::normalize(glm::cross(z, glm::vec3(0.f, 1.f, 0.f)));
    const glm::vec3 y = glm::cross(z, x);
    glm::mat4 worldFromCamera(1.f);
    worldFromCamera[0] = glm::vec4(x, 0.f);
    worldFromCamera[1] = glm::vec4(y, 0.f);
    worldFromCamera[2] = glm::vec4(z, 0.f);
    worldFromCamera[3] = glm::vec4(centre, 1.f);
    return glm::inverse(worldFromCamera);
}

float TuftWind::gust(double t_s, float phase_rad) const {
    const double w = 2.0 * std::numbers::pi * gustFrequency_hz * t_s;
    const double gustShape = 0.5 * (1.0 - std::cos(w + phase_rad));
    const double turbulence =
        (1.0 - kTurbulenceShare) +
        kTurbulenceShare * std::sin(kTurbulenceFrequencyRatio * w + 1.3 * phase_rad);
    return static_cast<float>(gustShape * turbulence);
}

QuadraticBezier spineWithLength(const glm::vec3& v0, const glm::vec3& baseDirection,
                                const glm::vec3& v2, float length_m) {
    const float chord = glm::length(v2 - v0);
    if (!(length_m > 0.f) || !(chord < length_m))
        throw std::invalid_argument("spineWithLength: need |v2 - v0| < length, got chord " +
                                    std::to_string(chord) + " m, length " +
                                    std::to_string(length_m) + " m");
    const glm::vec3 dir = glm::normalize(baseDirection);
    // |B| grows from the chord (v1 = v0) as v1 moves out along the base direction; at 2 L the
    // curve passes beyond L from v0 and back, so it is longer than L: a bracket.
    double lo = 0.0, hi = 2.0 * length_m;
    for (int i = 0; i < kLengthBisectionSteps; ++i) {
        const double mid = 0.5 * (lo + hi);
        const QuadraticBezier c{v0, v0 + dir * static_cast<float>(mid), v2};
        (c.length() < length_m ? lo : hi) = mid;
    }
    return {v0, v0 + dir * static_cast<float>(0.5 * (lo + hi)), v2};
}

QuadraticBezier SyntheticBlade::spineInCamera_m() const {
    const auto apply = [this](const glm::vec3& p) {
        return glm::vec3(cameraFromBlade * glm::vec4(p, 1.f));
    };
    return {apply(archetype.spine_m.v0), apply(archetype.spine_m.v1), apply(archetype.spine_m.v2)};
}

TriangleMesh SyntheticBlade::meshInCamera() const {
    return transformed(bladeMesh(archetype, mesh), cameraFromBlade);
}

std::vector<synth::LabelledMesh> SyntheticTuft::meshes() const {
    std::vector<synth::LabelledMesh> out = scenery;
    for (const SyntheticBlade& b : blades)
        out.push_back(placeBlade(bladeMesh(b.archetype, b.mesh), b.cameraFromBlade, b.id));
    return out;
}

SyntheticTuft buildTuft(const TuftSpec& spec, int frame) {
    if (spec.blades.empty()) throw std::invalid_argument("buildTuft: the tuft has no blades");
    if (spec.blades.size() > std::numeric_limits<std::uint16_t>::max())
        throw std::invalid_argument("buildTuft: more blades than 16-bit labels can tell apart");
    if (frame < 0) throw std::invalid_argument("buildTuft: frame must be >= 0");

    SyntheticTuft tuft;
    tuft.cameraFromWorld = spec.camera.cameraFromWorld();
    tuft.timestamp_s = frame / static_cast<double>(spec.wind.frameRate_hz);

    for (std::size_t i = 0; i < spec.blades.size(); ++i) {
        const BladePlacement& placement = spec.blades[i];
        const glm::mat4 rotation = bladeRotation(placement);
        const glm::mat4 worldFromBlade =
            glm::translate(glm::mat4(1.f), placement.base_m) * rotation;

        SyntheticBlade blade;
        blade.id = static_cast<std::uint16_t>(i + 1);
        blade.archetype = placement.archetype;
        blade.mesh = placement.mesh;
        QuadraticBezier& spine = blade.archetype.spine_m;
        const float length_m = spine.length();
        const glm::vec3 baseDirection = restBaseDirection(spine);

        if (placement.curlTowardCamera_rad != 0.f) {
            // Blade-local +Z faces the camera unless the blade was turned round to bend toward
            // world -X; the tip turns about the local X axis through v0 toward the camera.
            const float angle = placement.bendsTowardPlusX ? placement.curlTowardCamera_rad
                                                           : -placement.curlTowardCamera_rad;
            const glm::mat4 curl = glm::rotate(glm::mat4(1.f), angle, glm::vec3(1.f, 0.f, 0.f));
            const glm::vec3 v2 = glm::vec3(curl * glm::vec4(spine.v2 - spine.v0, 0.f)) + spine.v0;
            spine = spineWithLength(spine.v0, baseDirection, v2, length_m);
        }
        if (spec.wind.tipDisplacementPerHeight > 0.f) {
            const float push_m = spec.wind.tipDisplacementPerHeight * length_m *
                                 spec.wind.gust(tuft.timestamp_s, placement.gustPhase_rad);
            const glm::vec3 pushLocal =
                glm::vec3(glm::transpose(rotation) * glm::vec4(push_m, 0.f, 0.f, 0.f));
            glm::vec3 chord = spine.v2 + pushLocal - spine.v0;
            const float maxChord_m = kMaxChordFraction * length_m;
            if (glm::length(chord) > maxChord_m) chord *= maxChord_m / glm::length(chord);
            spine = spineWithLength(spine.v0, baseDirection, spine.v0 + chord, length_m);
        }
        blade.cameraFromBlade = tuft.cameraFromWorld * worldFromBlade;
        tuft.blades.push_back(std::move(blade));
    }

    if (spec.scenery) {
        const glm::mat4& cfw = tuft.cameraFromWorld;
        const float s = kSceneryHalfWidth_m, zWall = -spec.wallBehind_m;
        const glm::vec3 centre = glm::vec3(glm::inverse(cfw)[3]);
        const float zNear = centre.z - kGroundNearGap_m;
        tuft.scenery.push_back(quad(cfw, {-s, 0.f, zWall}, {s, 0.f, zWall}, {s, 0.f, zNear},
                                    {-s, 0.f, zNear}));  // ground
        tuft.scenery.push_back(quad(cfw, {-s, 0.f, zWall}, {s, 0.f, zWall},
                                    {s, kWallHeight_m, zWall},
                                    {-s, kWallHeight_m, zWall}));  // back wall
    }
    return tuft;
}

}  // namespace meadow::synth
