// Position-based dynamics of a blade skeleton chain; the model is documented in
// chain_simulation.h.
#include "meadow/modeling/chain_simulation.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <stdexcept>
#include <string>

#include "meadow/core/random.h"

namespace meadow::modeling {
namespace {

// Knots 0 and 1 are clamped: the root and the direction the blade leaves the ground.
constexpr int kClampedKnots = 2;

// One distance constraint projection (Mueller et al. 2007, Eq. 9-10) between p[i] and p[j].
void projectDistance(std::vector<glm::vec3>& p, const std::vector<float>& invMass, int i, int j,
                     float rest, float stiffness) {
    const float wSum = invMass[i] + invMass[j];
    if (wSum <= 0.f) return;
    const glm::vec3 d = p[i] - p[j];
    const float len = glm::length(d);
    if (len <= 1e-9f) return;
    const glm::vec3 correction = stiffness * (len - rest) / (len * wSum) * d;
    p[i] -= invMass[i] * correction;
    p[j] += invMass[j] * correction;
}

}  // namespace

KnotTrajectories simulateChain(const std::vector<glm::vec3>& rest,
                               const ChainSimulationParams& params) {
    const int n = static_cast<int>(rest.size());
    if (n < 3)
        throw std::invalid_argument("simulateChain: need >= 3 knots, got " + std::to_string(n));
    if (params.frames < 1 || params.substeps < 1 || params.iterations < 1 ||
        !(params.frameTime_s > 0.f))
        throw std::invalid_argument(
            "simulateChain: frames, substeps, iterations and frameTime_s must be positive");

    std::vector<float> restLength(static_cast<std::size_t>(n - 1)),
        restBend(static_cast<std::size_t>(n - 2));
    std::vector<float> heightFraction(static_cast<std::size_t>(n), 0.f);
    for (int i = 0; i + 1 < n; ++i) restLength[i] = glm::distance(rest[i], rest[i + 1]);
    for (int i = 0; i + 2 < n; ++i) restBend[i] = glm::distance(rest[i], rest[i + 2]);
    for (int i = 1; i < n; ++i) heightFraction[i] = heightFraction[i - 1] + restLength[i - 1];
    const float total = heightFraction.back();
    for (float& f : heightFraction) f = total > 0.f ? f / total : 0.f;

    std::vector<float> invMass(static_cast<std::size_t>(n), 1.f);
    for (int i = 0; i < kClampedKnots; ++i) invMass[i] = 0.f;
    std::vector<float> recovery(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        // Cantilever-like: stiffness falls quadratically from root to tip.
        const float s = 1.f - heightFraction[i];
        recovery[i] = params.recoveryTip_per_s2 +
                      (params.recoveryBase_per_s2 - params.recoveryTip_per_s2) * s * s;
    }

    const glm::vec3 up = glm::normalize(params.up);
    glm::vec3 windDir = params.windDirection - glm::dot(params.windDirection, up) * up;
    windDir = glm::length(windDir) > 1e-6f ? glm::normalize(windDir) : glm::vec3(1.f, 0.f, 0.f);
    const glm::vec3 crossDir = glm::normalize(glm::cross(up, windDir));

    Rng rng(params.seed);
    glm::vec3 turbulence{0.f};
    const float dt = params.frameTime_s / static_cast<float>(params.substeps);
    const float decay = std::exp(-params.frameTime_s / params.turbulenceTime_s);

    std::vector<glm::vec3> x = rest, v(rest.size(), glm::vec3(0.f)), p(rest.size());
    KnotTrajectories out;
    out.reserve(static_cast<std::size_t>(params.frames));
    float t = 0.f;
    for (int frame = 0; frame < params.frames; ++frame) {
        // Ornstein-Uhlenbeck turbulence, stationary standard deviation turbulence_mps.
        const float kick = params.turbulence_mps * std::sqrt(1.f - decay * decay);
        turbulence = decay * turbulence + kick * (rng.normal() * windDir + rng.normal() * crossDir);
        for (int step = 0; step < params.substeps; ++step) {
            const float gust = std::sin(std::numbers::pi_v<float> * params.gustFrequency_hz * t);
            const glm::vec3 wind =
                (params.windMean_mps + params.gustAmplitude_mps * gust * gust) * windDir +
                turbulence;
            const float damp = std::exp(-params.damping_per_s * dt);
            for (int i = 0; i < n; ++i) {
                if (invMass[i] == 0.f) {
                    p[i] = x[i];
                    continue;
                }
                const float windScale =
                    params.windAtBase + (1.f - params.windAtBase) * heightFraction[i];
                const glm::vec3 a = params.gravity_mps2 +
                                    params.drag_per_s * (windScale * wind - v[i]) +
                                    recovery[i] * (rest[i] - x[i]);
                v[i] = (v[i] + dt * a) * damp;
                p[i] = x[i] + dt * v[i];
            }
            for (int it = 0; it < params.iterations; ++it) {
                for (int i = 0; i + 1 < n; ++i)
                    projectDistance(p, invMass, i, i + 1, restLength[i], params.stretchStiffness);
                for (int i = 0; i + 2 < n; ++i)
                    projectDistance(p, invMass, i, i + 2, restBend[i], params.bendStiffness);
            }
            for (int i = 0; i < n; ++i) {
                v[i] = (p[i] - x[i]) / dt;
                x[i] = p[i];
            }
            t += dt;
        }
        out.push_back(x);
    }
    return out;
}

}  // namespace meadow::modeling
