#include "meadow/synth/labelled_mesh.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace meadow::synth {
namespace {

TEST(LabelledMesh, PlacementIsRigidAndKeepsTheLabel) {
    modeling::Archetype a;
    a.name = "leaf";
    a.spine_m = {{0, 0, 0}, {0, 0.1f, 0}, {0.06f, 0.14f, 0}};
    a.width.width_m = {0.008f, 0.012f, 0.015f, 0.016f, 0.016f, 0.015f,
                       0.013f, 0.011f, 0.008f, 0.004f, 0.f};
    const modeling::TriangleMesh local = modeling::bladeMesh(a);
    glm::mat4 cameraFromBlade = glm::translate(glm::mat4(1.f), glm::vec3(0.1f, 0.2f, 0.8f));
    cameraFromBlade = glm::rotate(cameraFromBlade, 0.7f, glm::normalize(glm::vec3(1, 2, 3)));
    const LabelledMesh placed = placeBlade(a, cameraFromBlade, 7);
    EXPECT_EQ(placed.label, 7);
    ASSERT_EQ(placed.positions_m.size(), local.positions_m.size());
    EXPECT_EQ(placed.triangles, local.triangles);
    for (std::size_t i = 1; i < local.positions_m.size(); ++i)
        EXPECT_NEAR(glm::length(placed.positions_m[i] - placed.positions_m[0]),
                    glm::length(local.positions_m[i] - local.positions_m[0]), 1e-6f);
}

}  // namespace
}  // namespace meadow::synth
