#include "meadow/synth/labelled_mesh.h"

namespace meadow::synth {

LabelledMesh placeBlade(const modeling::TriangleMesh& bladeLocal, const glm::mat4& cameraFromBlade,
                        std::uint16_t label) {
    LabelledMesh out;
    out.label = label;
    out.triangles = bladeLocal.triangles;
    out.positions_m.reserve(bladeLocal.positions_m.size());
    for (const glm::vec3& p : bladeLocal.positions_m)
        out.positions_m.push_back(glm::vec3(cameraFromBlade * glm::vec4(p, 1.f)));
    return out;
}

LabelledMesh placeBlade(const modeling::Archetype& archetype, const glm::mat4& cameraFromBlade,
                        std::uint16_t label, const modeling::BladeMeshOptions& options) {
    return placeBlade(modeling::bladeMesh(archetype, options), cameraFromBlade, label);
}

}  // namespace meadow::synth
