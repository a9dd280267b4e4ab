#pragma once
// Settings of the per-blade physics (Jahrmann & Wimmer 2017, Sec. 5) as a user sets them; the
// physics pass packs them into shaders/shared/physics_params.h's PhysicsParamsGpu each frame.
// Units are in the names; defaults give a light breeze under earth gravity.
#include <glm/vec3.hpp>

namespace meadow::runtime {

struct PhysicsSettings {
    // Environmental gravity, Eq. (3): direction D, centre C, blended by gravityCenterMix (t).
    glm::vec3 gravityDirection{0.f, -1.f, 0.f};
    float gravity_mps2 = 9.81f;
    glm::vec3 gravityCenter_m{0.f, -6.371e6f, 0.f};  // the earth's centre below a +Y-up scene
    float gravityCenter_mps2 = 9.81f;
    float gravityCenterMix = 0.f;  // t: 0 = direction only, 1 = centre only
    // The paper's mass m scales gravity against the per-blade stiffness s (1/s): front gravity
    // (Eq. (4)) moves a blade's tip about m g / (4 s) over its front. 0.02 with the seeding's
    // s ~ 0.6-1 gives 5-8 cm.
    float mass = 0.02f;

    // Wind, Sec. 5.1: a directional travelling wave plus a point source (a fan, a helicopter).
    glm::vec3 windDirection{1.f, 0.f, 0.f};
    float windWave_mps = 0.3f;  // reaches ~0.3 / s m of tip travel at full alignment
    glm::vec3 windSource_m{0.f, 0.f, 0.f};
    float windSource_mps = 0.f;
    float windWavelength_m = 4.f;
    float windFrequency_hz = 0.5f;  // the waves' and rings' frequency; 0: a wave that stands still
    float windSourceRadius_m = 5.f;
    // Gusts and turbulence (Habel, Wimmer & Jeschke 2007): noise fields the wind carries across
    // the meadow. Gusts are patches of stronger wind along the wind's direction, about
    // windGustSize_m across, travelling at windGustSpeed_mps; turbulence stirs the blades in
    // every horizontal direction at a smaller scale. 0 amplitude: none.
    float windGust_mps = 0.f;
    float windGustSize_m = 3.f;
    float windGustSpeed_mps = 2.f;
    float windTurbulence_mps = 0.f;
    float windTurbulenceSize_m = 0.6f;

    // Collisions, Sec. 5.1: the collision strength eta decays by etaDecay_per_s each second, grows
    // by etaGain |d| / h per collision; recovery is weakened to max(1 - eta, recoveryFloor).
    float etaDecay_per_s = 0.5f;
    float etaGain = 1.f;
    float recoveryFloor = 0.1f;

    // Validation, Eq. (13): true = exact arc length (keeps the length within float precision of
    // the height), false = the paper's degree-2 estimate (errs by 1-8 % on strongly bent blades).
    bool exactLength = true;
};

// A sphere that pushes blades (Eq. (9)).
struct CollisionSphere {
    glm::vec3 center_m{0.f};
    float radius_m = 0.f;
};

class GlContext;
class Renderer;

// Plugs the GPU physics pass (physics.comp) into `renderer`, with settings from its scene file
// (gravity, collision decay, wind) and the scene's colliders. Throws RuntimeError when the
// shader does not compile.
void installPhysicsPass(Renderer& renderer, GlContext& context);

}  // namespace meadow::runtime
