#pragma once
// CPU z-buffer rasteriser for the simulated sensor: the nearest surface per pixel, with its
// exact (perspective-correct) depth, its mesh label and its camera-facing unit normal.
#include <glm/vec3.hpp>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "meadow/capture/intrinsics.h"
#include "meadow/synth/labelled_mesh.h"

namespace meadow::synth::detail {

using capture::Intrinsics;

struct RasterImage {
    cv::Mat1f depth_m;  // z of the nearest surface in the viewer's frame, 0 where nothing
    cv::Mat1w labels;   // its LabelledMesh::label (only when attributes were asked for)
    cv::Mat3f normals;  // its unit normal, pointing towards the viewer (same condition)
};

// Empty when the mesh can be rasterised; otherwise what is wrong with it (index out of range,
// non-finite vertex), naming the mesh by its position in the list.
std::string meshProblem(const LabelledMesh& mesh, std::size_t meshIndex);

// Rasterises meshes (camera space, metres) as seen by a pinhole viewer at viewerOrigin_m with
// the camera's orientation and the given intrinsics. withAttributes = false fills depth only
// (the projector's view needs no labels or normals). Pixel (i, j) samples the point (i, j),
// as Intrinsics puts pixel centres at integer coordinates. Triangles are two-sided and clipped
// at a near plane, so meshes that reach behind the viewer are fine.
// Precondition: every mesh passes meshProblem().
RasterImage rasterise(const std::vector<LabelledMesh>& meshes, const Intrinsics& intrinsics,
                      const glm::vec3& viewerOrigin_m, bool withAttributes);

}  // namespace meadow::synth::detail
