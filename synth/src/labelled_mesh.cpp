#include "meadow/synth/labelled_mesh.h"

namespace meadow::synth {

void addQuad(LabelledMesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    const auto base = static_cast<unsigned>(mesh.positions_m.size());
    mesh.positions_m.insert(mesh.positions_m.end(), {a, b, c, d});
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
}

LabelledMesh boxMesh(glm::vec3 lo, glm::vec3 hi, std::uint16_t label) {
    LabelledMesh m;
    m.label = label;
    addQuad(m, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z});
    addQuad(m, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
    addQuad(m, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {lo.x, lo.y, hi.z});
    addQuad(m, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z});
    addQuad(m, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z});
    addQuad(m, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
    return m;
}

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
