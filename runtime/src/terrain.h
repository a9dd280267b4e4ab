#pragma once
// The height field of a tiled scene (scene.h, TerrainDescription): heights on a regular grid over
// the terrain's XZ rectangle, the mesh drawn for the ground, and the height range of each tile
// (the tiles' boxes for culling). The GPU reads the same grid as a texture, bilinearly, so blades
// stand on the drawn ground.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <opencv2/core/mat.hpp>

#include "meadow/runtime/scene.h"
#include "scene_mesh.h"

namespace meadow::runtime {

struct HeightField {
    cv::Mat height_m;  // CV_32F, samples x samples; row r at z = min.z + r * spacing.y
    glm::vec2 minXZ_m{0.f};
    glm::vec2 maxXZ_m{1.f};

    [[nodiscard]] glm::vec2 spacing_m() const;
    // Bilinear between the four nearest samples, clamped at the border.
    [[nodiscard]] float heightAt(glm::vec2 xz_m) const;
    // Unit normal from the central differences of heightAt.
    [[nodiscard]] glm::vec3 normalAt(glm::vec2 xz_m) const;
};

// Value noise in octaves: the largest hills featureSize_m across, each finer octave half the size
// and half the height; heights scaled to span relief_m. Deterministic for a seed.
HeightField makeHeightField(const TerrainDescription& terrain);

// Two triangles per grid cell, normals from the height field.
TriangleMesh terrainMesh(const HeightField& field);

// The lowest and highest height under each tile of side tileSize_m laid from the terrain's min
// corner: CV_32FC2 (min, max), tilesZ x tilesX.
cv::Mat tileHeightRanges(const HeightField& field, float tileSize_m);

}  // namespace meadow::runtime
