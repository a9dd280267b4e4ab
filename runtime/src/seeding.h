#pragma once
// Planting blades on triangle meshes (Jahrmann & Wimmer 2017, Sec. 4): area-weighted positions,
// tufts by Poisson-disk sampling on the surface, single blades at random, an optional density
// map with per-blade thresholds (Boulanger et al.), archetype by weight or by an archetype map
// (value k at the root: archetype k), random direction,
// height and width scale; the initial pose is the archetype's rest shape on the surface.
#include <cstdint>
#include <glm/vec3.hpp>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "meadow/modeling/archetype.h"
#include "meadow/runtime/scene.h"
#include "scene_mesh.h"
#include "shared/blade_types.h"

namespace meadow::runtime {

struct SeededBlade {
    glm::vec3 root_m{0.f};           // v0, on the surface (world)
    glm::vec3 up{0.f, 1.f, 0.f};     // surface normal at the root (world, unit)
    float directionAngle_rad = 0.f;  // turns the width direction about up (bladeWidthDirection)
    std::uint32_t archetype = 0;
    float heightScale = 1.f;
    float widthScale = 1.f;
    float stiffness = 1.f;
    std::uint32_t mesh = 0;  // which grass mesh and triangle it grows on
    std::uint32_t triangle = 0;
    bool inTuft = false;
    glm::vec3 tuftCenter_m{0.f};  // the Poisson-disk centre of its tuft (inTuft only)
};

struct SeedingInput {
    const std::vector<TriangleMesh>* meshes = nullptr;
    const BladeSeeding* params = nullptr;
    const std::vector<modeling::Archetype>* archetypes = nullptr;
    const std::vector<float>* archetypeWeights = nullptr;
    cv::Mat densityMap;               // CV_32F in [0, 1], rows along z, cols along x; empty = none
    cv::Mat archetypeMap;             // CV_8U archetype indices (loadArchetypeMap); empty = weights
    ArchetypeMap archetypeMapExtent;  // where archetypeMap lies in world XZ
    std::size_t countMultiple = 1;    // the blade count is made a multiple of this
};

// Deterministic for a given input (the seed is in params). Throws RuntimeError when the meshes
// have no area or the scene would have no blades.
std::vector<SeededBlade> seedBlades(const SeedingInput& input);

// The blade's width direction, the C++ mirror of bladeWidthDirection() in common_blade.glsl.
glm::vec3 bladeWidthDirection(glm::vec3 up, float directionAngle_rad);

// The archetype's rest shape placed on the surface: v0 at the root, the archetype's +Y along the
// surface normal, and its in-face bend (+X) turned into a droop about the blade's width axis (a
// captured blade lies flat in the camera image; a growing blade bends over its face normal).
gpu::BladeGpu restPose(const SeededBlade& blade, const modeling::Archetype& archetype);
gpu::BladeRestGpu restState(const SeededBlade& blade, const gpu::BladeGpu& pose);
gpu::ArchetypeGpu archetypeForGpu(const modeling::Archetype& archetype, bool useProfile);

}  // namespace meadow::runtime
