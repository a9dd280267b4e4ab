#pragma once
// Short simulated trajectories of a blade skeleton, the input of skeleton refining by movement
// similarity (Fan & Sheng 2017, Sec. 4.4 simulate the captured skeleton to see which knots move
// together). The model is position-based dynamics (Mueller, Heidelberger, Hennix & Ratcliff
// 2007, "Position Based Dynamics", Algorithm 1) on the chain of knots:
//   - the base knot and the first segment are clamped (the root and its direction),
//   - segments are inextensible: distance constraints between knots i, i+1 (stiffness k_stretch),
//   - bending: distance constraints between knots i, i+2 to their rest distance (k_bend),
//   - external accelerations: gravity; drag toward a gusting wind velocity whose speed grows with
//     height above the base (wind near the ground is slower); and a recovery acceleration toward
//     the knot's rest position whose stiffness falls from base to tip, so the chain behaves like
//     a cantilever (stiff root, compliant tip) instead of a rope. The recovery is the per-knot
//     counterpart of Jahrmann & Wimmer 2017's recovery force (their Eq. 3).
// Deterministic for a given seed.
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace meadow::modeling {

struct ChainSimulationParams {
    int frames = 60;                 // n in Fan & Sheng's Eq. 1-3
    float frameTime_s = 1.f / 30.f;  // a 30 Hz capture: 60 frames = 2 s, one gust cycle
    int substeps = 4;                // PBD steps per frame
    int iterations = 8;              // constraint projection sweeps per step
    float stretchStiffness = 1.f;    // k_stretch in [0, 1]
    float bendStiffness = 0.5f;      // k_bend in [0, 1]
    float damping_per_s = 2.f;       // velocity decay rate
    glm::vec3 gravity_mps2{0.f, -9.81f, 0.f};
    glm::vec3 up{0.f, 1.f, 0.f};  // blade-local +Y; the wind blows across it
    glm::vec3 windDirection{1.f, 0.f,
                            0.35f};  // normalised internally, made horizontal (perp. to up)
    float windMean_mps = 1.0f;
    float gustAmplitude_mps = 2.5f;  // gust speed on top of the mean, sin^2 envelope
    float gustFrequency_hz = 0.5f;
    float turbulence_mps = 0.6f;    // Ornstein-Uhlenbeck gusts, per frame
    float turbulenceTime_s = 0.3f;  // correlation time of the turbulence
    float windAtBase = 0.3f;        // wind speed fraction at the base; 1 at the tip
    float drag_per_s = 6.f;         // acceleration per m/s of relative wind speed
    // Recovery stiffness (1/s^2) at the base and at the tip: deflection ~ acceleration / k, so a
    // 12 m/s^2 gust bends the tip by ~3 cm, a third of a 10 cm blade.
    float recoveryBase_per_s2 = 4000.f;
    float recoveryTip_per_s2 = 400.f;
    std::uint64_t seed = 1;
};

// Positions of every knot at each frame: result[frame][knot]. Frame 0 is the first simulated
// frame (not the rest shape). Requires >= 3 knots and frames >= 1.
using KnotTrajectories = std::vector<std::vector<glm::vec3>>;
KnotTrajectories simulateChain(const std::vector<glm::vec3>& restKnots_m,
                               const ChainSimulationParams& params = {});

}  // namespace meadow::modeling
