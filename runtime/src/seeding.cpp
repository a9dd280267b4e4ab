#include "seeding.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numeric>
#include <unordered_map>

#include "ground_maps.h"
#include "meadow/core/random.h"
#include "meadow/runtime/error.h"
#include "short_number.h"

namespace meadow::runtime {
namespace {

static_assert(BLADE_SHAPE_ONE_SIDED_QUADRATIC ==
                      static_cast<int>(modeling::AnalyticShape::OneSidedQuadratic) &&
                  BLADE_SHAPE_TRIANGLE_TIP ==
                      static_cast<int>(modeling::AnalyticShape::TriangleTip),
              "shaders/shared/blade_types.h numbers the shapes as modeling::AnalyticShape does");

constexpr float kTwoPi = 6.28318530718f;
// Dart throwing gives up after this many rejected candidates per wanted tuft (the surface is
// then saturated at the Poisson-disk spacing).
constexpr int kPoissonAttemptsPerTuft = 30;
// With no spacing given, tuft centres are kept this fraction of the mean spacing sqrt(A / T)
// apart: random dart throwing saturates near 55 % of the hexagonal packing density, so a tighter
// disk than the mean spacing is needed to place all T tufts.
constexpr float kDerivedSpacingFraction = 0.7f;
// Tuft blades lean outward from the tuft centre within this angle of the outward direction (rad).
constexpr float kTuftLeanJitter_rad = 0.6f;
// Top-up singles are tried this many times per missing blade before the count is trimmed instead.
constexpr int kTopUpAttemptsPerBlade = 50;

struct SurfacePoint {
    glm::vec3 position_m;
    glm::vec3 normal;
    std::uint32_t mesh, triangle;
};

// Area-weighted surface sampling: a triangle with probability area / total area, then a uniform
// point in it (the square-root warp of the barycentric coordinates).
class SurfaceSampler {
public:
    explicit SurfaceSampler(const std::vector<TriangleMesh>& meshes) : meshes_(meshes) {
        double total = 0.0;
        for (std::uint32_t m = 0; m < meshes.size(); ++m)
            for (std::uint32_t t = 0; t < meshes[m].triangles.size(); ++t) {
                const double a = triangleArea_m2(meshes[m], t);
                if (!(a > 0.0)) continue;  // degenerate triangles grow nothing
                total += a;
                cumulative_.push_back(total);
                triangles_.emplace_back(m, t);
            }
        area_m2_ = total;
    }
    [[nodiscard]] double area_m2() const { return area_m2_; }

    SurfacePoint sample(Rng& random) const {
        const double x = static_cast<double>(random.uniform()) * area_m2_;
        const std::size_t k = std::min<std::size_t>(
            std::upper_bound(cumulative_.begin(), cumulative_.end(), x) - cumulative_.begin(),
            cumulative_.size() - 1);
        const auto [m, t] = triangles_[k];
        const TriangleMesh& mesh = meshes_[m];
        const glm::uvec3 tri = mesh.triangles[t];
        const float r1 = std::sqrt(random.uniform()), r2 = random.uniform();
        const float a = 1.f - r1, b = r1 * (1.f - r2), c = r1 * r2;
        const glm::vec3 p =
            a * mesh.positions_m[tri.x] + b * mesh.positions_m[tri.y] + c * mesh.positions_m[tri.z];
        glm::vec3 n = a * mesh.normals[tri.x] + b * mesh.normals[tri.y] + c * mesh.normals[tri.z];
        if (!(glm::dot(n, n) > 1e-12f))
            n = glm::cross(mesh.positions_m[tri.y] - mesh.positions_m[tri.x],
                           mesh.positions_m[tri.z] - mesh.positions_m[tri.x]);
        return {p, glm::normalize(n), m, t};
    }

private:
    const std::vector<TriangleMesh>& meshes_;
    std::vector<double> cumulative_;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> triangles_;
    double area_m2_ = 0.0;
};

// Poisson-disk acceptance on the surface: a hash grid of cells of the disk radius, so each
// candidate is checked against the 27 neighbouring cells only.
class PoissonGrid {
public:
    explicit PoissonGrid(float radius_m) : radius_m_(radius_m) {}
    bool tryInsert(glm::vec3 p) {
        const glm::ivec3 c = cell(p);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    auto it = cells_.find(key(c + glm::ivec3(dx, dy, dz)));
                    if (it == cells_.end()) continue;
                    for (const glm::vec3& q : it->second)
                        if (glm::dot(p - q, p - q) < radius_m_ * radius_m_) return false;
                }
        cells_[key(c)].push_back(p);
        return true;
    }

private:
    glm::ivec3 cell(glm::vec3 p) const { return glm::ivec3(glm::floor(p / radius_m_)); }
    static std::uint64_t key(glm::ivec3 c) {
        return (static_cast<std::uint64_t>(c.x & 0x1fffff) << 42) |
               (static_cast<std::uint64_t>(c.y & 0x1fffff) << 21) |
               static_cast<std::uint64_t>(c.z & 0x1fffff);
    }
    float radius_m_;
    std::unordered_map<std::uint64_t, std::vector<glm::vec3>> cells_;
};

std::uint32_t pickArchetype(const std::vector<float>& cumulativeWeights, Rng& random) {
    const float x = random.uniform() * cumulativeWeights.back();
    const auto it = std::upper_bound(cumulativeWeights.begin(), cumulativeWeights.end(), x);
    return static_cast<std::uint32_t>(
        std::min<std::size_t>(it - cumulativeWeights.begin(), cumulativeWeights.size() - 1));
}

// Density map value at a world point (nearest lookup: the map is a mask, and a blade's threshold
// already dithers its edges).
float densityAt(const cv::Mat& map, const DensityMap& extent, glm::vec3 p) {
    const cv::Point texel = texelAt(extent, map.size(), p);
    return map.at<float>(texel.y, texel.x);
}

// What one blade costs on its way to the GPU: its seed here, its state and rest pose there, and a
// slot in the visible-index buffer.
constexpr double kBytesPerBlade =
    sizeof(SeededBlade) + sizeof(gpu::BladeGpu) + sizeof(gpu::BladeRestGpu) + sizeof(std::uint32_t);
// Share of the machine's memory a scene's blades may take.
constexpr double kMemoryShare = 0.5;

std::string shortBytes(double bytes) {
    const char* units[] = {"B", "KB", "MB", "GB", "TB", "PB", "EB"};
    int u = 0;
    while (bytes >= 1024.0 && u < 6) bytes /= 1024.0, ++u;
    return shortNumber(static_cast<float>(bytes)) + " " + units[u];
}

// Refuses, before anything is allocated, a scene whose blades would not fit in memory.
void checkBladeMemory(float density_per_m2, double area_m2) {
    const double blades = static_cast<double>(density_per_m2) * area_m2;
    const double needed = blades * kBytesPerBlade;
    const double available = static_cast<double>(::sysconf(_SC_PHYS_PAGES)) *
                             static_cast<double>(::sysconf(_SC_PAGESIZE));
    if (needed <= kMemoryShare * available) return;
    throw RuntimeError("blades.density_per_m2 " + shortNumber(density_per_m2) + " over " +
                       shortNumber(static_cast<float>(area_m2)) + " m^2 of grass asks for " +
                       shortNumber(static_cast<float>(blades)) + " blades, about " +
                       shortBytes(needed) + " of memory: more than half of this machine's " +
                       shortBytes(available) + "; lower the density or the grass area");
}

}  // namespace

glm::vec3 bladeWidthDirection(glm::vec3 up, float directionAngle_rad) {
    const glm::vec3 axis =
        std::abs(up.z) < 0.9f ? glm::vec3(0.f, 0.f, 1.f) : glm::vec3(1.f, 0.f, 0.f);
    const glm::vec3 t = glm::normalize(glm::cross(up, axis));
    const glm::vec3 b = glm::cross(up, t);
    return std::cos(directionAngle_rad) * t + std::sin(directionAngle_rad) * b;
}

std::vector<SeededBlade> seedBlades(const SeedingInput& in) {
    const BladeSeeding& p = *in.params;
    const SurfaceSampler sampler(*in.meshes);
    if (!(sampler.area_m2() > 0.0)) {
        std::string names;
        for (const TriangleMesh& m : *in.meshes) names += (names.empty() ? "" : ", ") + m.origin;
        throw RuntimeError(
            "the grass meshes (" + names +
            ") have no surface area to grow grass on; name a mesh with non-degenerate triangles");
    }
    std::vector<float> cumulativeWeights(in.archetypeWeights->size());
    std::partial_sum(in.archetypeWeights->begin(), in.archetypeWeights->end(),
                     cumulativeWeights.begin());

    checkBladeMemory(p.density_per_m2, sampler.area_m2());
    Rng random(p.seed);
    const auto wanted =
        static_cast<std::size_t>(std::llround(p.density_per_m2 * sampler.area_m2()));
    std::vector<SeededBlade> blades;
    blades.reserve(wanted + in.countMultiple);

    auto keep = [&](glm::vec3 position) {
        // Each blade draws its own density threshold (Boulanger et al.): it grows where the map
        // is at least that dense, so the map's grey levels become blade densities.
        const float threshold = random.uniform();
        return in.densityMap.empty() || !p.densityMap ||
               densityAt(in.densityMap, *p.densityMap, position) > threshold;
    };
    auto makeBlade = [&](const SurfacePoint& s, glm::vec3 root, float angle, bool tuft) {
        SeededBlade b;
        b.root_m = root;
        b.up = s.normal;
        b.directionAngle_rad = angle;
        // Drawn even under an archetype map, so that a map changes which archetype grows where
        // and nothing else (positions, sizes and directions stay those of the same seed).
        b.archetype = pickArchetype(cumulativeWeights, random);
        if (!in.archetypeMap.empty()) {
            const cv::Point texel = texelAt(in.archetypeMapExtent, in.archetypeMap.size(), root);
            const std::uint8_t k = in.archetypeMap.at<std::uint8_t>(texel.y, texel.x);
            if (k != kArchetypeByWeights) b.archetype = k;
        }
        b.heightScale = random.uniform(p.heightScale.x, p.heightScale.y);
        b.widthScale = random.uniform(p.widthScale.x, p.widthScale.y);
        b.stiffness = random.uniform(p.stiffness.x, p.stiffness.y);
        b.mesh = s.mesh;
        b.triangle = s.triangle;
        b.inTuft = tuft;
        if (tuft) b.tuftCenter_m = s.position_m;  // s is the tuft's centre for tuft blades
        return b;
    };
    auto addSingle = [&] {
        const SurfacePoint s = sampler.sample(random);
        const float angle = random.uniform() * kTwoPi;
        if (keep(s.position_m)) blades.push_back(makeBlade(s, s.position_m, angle, false));
    };

    // Tufts: Poisson-disk centres on the surface, blades scattered within the tuft radius in the
    // tangent plane, each drooping away from the centre.
    const float meanTuftBlades = 0.5f * static_cast<float>(p.tuftBladesMin + p.tuftBladesMax);
    const auto tuftBladesWanted =
        static_cast<std::size_t>(std::llround(p.tuftFraction * static_cast<double>(wanted)));
    const auto tuftsWanted = static_cast<std::size_t>(
        std::llround(static_cast<double>(tuftBladesWanted) / meanTuftBlades));
    if (tuftsWanted > 0) {
        const float spacing_m =
            p.tuftSpacing_m > 0.f
                ? p.tuftSpacing_m
                : kDerivedSpacingFraction *
                      static_cast<float>(std::sqrt(sampler.area_m2() / tuftsWanted));
        PoissonGrid grid(spacing_m);
        std::size_t tufts = 0, tuftBlades = 0;
        for (std::size_t attempt = 0; attempt < tuftsWanted * kPoissonAttemptsPerTuft &&
                                      tufts < tuftsWanted && tuftBlades < tuftBladesWanted;
             ++attempt) {
            const SurfacePoint centre = sampler.sample(random);
            if (!grid.tryInsert(centre.position_m)) continue;
            ++tufts;
            const glm::vec3 t = bladeWidthDirection(centre.normal, 0.f);
            const glm::vec3 b = glm::cross(centre.normal, t);
            const int count = random.integer(p.tuftBladesMin, p.tuftBladesMax);
            for (int i = 0; i < count; ++i) {
                const float r = p.tuftRadius_m * std::sqrt(random.uniform());
                const float phi = random.uniform() * kTwoPi;
                const glm::vec3 root =
                    centre.position_m + r * (std::cos(phi) * t + std::sin(phi) * b);
                // Droop direction = outward (cos phi, sin phi) in (t, b); see bladeWidthDirection:
                // the droop is cross(width, up) = -cos(theta) b + sin(theta) t.
                const float lean = phi + (random.uniform() - 0.5f) * kTuftLeanJitter_rad;
                const float angle = std::atan2(std::cos(lean), -std::sin(lean));
                if (keep(root)) {
                    blades.push_back(makeBlade(centre, root, angle, true));
                    ++tuftBlades;
                }
            }
        }
    }
    // Single blades fill the rest of the wanted count.
    const std::size_t singlesWanted = wanted > tuftBladesWanted ? wanted - tuftBladesWanted : 0;
    for (std::size_t i = 0; i < singlesWanted; ++i) addSingle();

    // Equal-size patches need a count that is a multiple of the patch size: top up with singles,
    // or trim when a sparse density map keeps rejecting them.
    const std::size_t m = std::max<std::size_t>(in.countMultiple, 1);
    if (blades.size() % m != 0) {
        const std::size_t target = (blades.size() / m + 1) * m;
        for (std::size_t attempt = 0;
             blades.size() < target && attempt < (target - blades.size()) * kTopUpAttemptsPerBlade;
             ++attempt)
            addSingle();
        if (blades.size() % m != 0) blades.resize(blades.size() / m * m);
    }
    if (blades.empty())
        throw RuntimeError(
            "the scene " + std::string(p.densityMap ? "(with its density map) " : "") +
            "grows no blades (area " + shortNumber(sampler.area_m2()) + " m^2, density " +
            shortNumber(p.density_per_m2) + " blades/m^2, patch size " + std::to_string(m) +
            "); raise blades.density_per_m2");
    return blades;
}

gpu::BladeGpu restPose(const SeededBlade& blade, const modeling::Archetype& archetype) {
    const glm::vec3 n = blade.up;
    const glm::vec3 w = bladeWidthDirection(n, blade.directionAngle_rad);
    const glm::vec3 d = glm::cross(w, n);  // droop direction: the blade's face normal
    // worldFromBlade: local X (in-face bend) -> d, local Y -> n, local Z -> -w (right-handed).
    auto worldFromBlade = [&](glm::vec3 local) {
        return blade.root_m + blade.heightScale * (local.x * d + local.y * n - local.z * w);
    };
    const modeling::QuadraticBezier& s = archetype.spine_m;
    gpu::BladeGpu g;
    const glm::vec3 v0 = worldFromBlade(s.v0), v1 = worldFromBlade(s.v1), v2 = worldFromBlade(s.v2);
    g.v0_height = glm::vec4(v0, archetype.height_m() * blade.heightScale);
    g.v1_width = glm::vec4(v1, archetype.width.maxWidth_m() * blade.widthScale);
    g.v2_stiffness = glm::vec4(v2, blade.stiffness);
    g.up_direction = glm::vec4(n, blade.directionAngle_rad);
    return g;
}

gpu::BladeRestGpu restState(const SeededBlade& blade, const gpu::BladeGpu& pose) {
    gpu::BladeRestGpu r;
    r.restV1_archetype = glm::vec4(glm::vec3(pose.v1_width), static_cast<float>(blade.archetype));
    r.restV2_eta = glm::vec4(glm::vec3(pose.v2_stiffness), 0.f);
    return r;
}

gpu::ArchetypeGpu archetypeForGpu(const modeling::Archetype& archetype, bool useProfile) {
    gpu::ArchetypeGpu g{};
    const float widest = archetype.width.maxWidth_m();
    for (int i = 0; i < ARCHETYPE_WIDTH_SAMPLES; ++i) {
        const float s = static_cast<float>(i) / (ARCHETYPE_WIDTH_SAMPLES - 1);
        g.widthProfile[i / 4][i % 4] = widest > 0.f ? archetype.width.at(s) / widest : 0.f;
    }
    g.shape = glm::vec4(static_cast<float>(archetype.nearestShape), archetype.tau,
                        useProfile ? 1.f : 0.f, 0.f);
    g.sides = glm::vec4(archetype.leftWidthFraction, archetype.twistAtTip_rad, 0.f, 0.f);
    return g;
}

}  // namespace meadow::runtime
