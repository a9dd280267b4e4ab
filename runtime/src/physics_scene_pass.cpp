#include "physics_scene_pass.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "physics_pass.h"

namespace meadow::runtime {

PhysicsSettings physicsSettingsOf(const SceneDescription& scene, const gpu::FrameGpu& frame) {
    PhysicsSettings s;
    const PhysicsDescription& p = scene.physics;
    s.gravityDirection = p.gravityDirection;
    s.gravity_mps2 = p.gravity_m_s2;
    s.gravityCenter_m = p.gravityCenter_m;
    s.gravityCenter_mps2 = p.gravityCenter_m_s2;
    s.gravityCenterMix = p.gravityCenterMix;
    s.etaDecay_per_s = p.collisionDecay_per_s;
    // Direction and wave amplitude come through the frame, where the renderer may vary them.
    s.windDirection = glm::vec3(frame.wind);
    s.windWave_mps = frame.wind.w;
    s.windWavelength_m = scene.wind.wavelength_m;
    s.windFrequency_hz = scene.wind.frequency_hz;
    s.windSource_m = scene.wind.source_m;
    s.windSource_mps = scene.wind.sourceAmplitude_m_s;
    s.windSourceRadius_m = scene.wind.sourceRadius_m;
    s.windGust_mps = scene.wind.gustAmplitude_m_s;
    s.windGustSize_m = scene.wind.gustSize_m;
    s.windGustSpeed_mps = scene.wind.gustSpeed_m_s;
    s.windTurbulence_mps = scene.wind.turbulenceAmplitude_m_s;
    s.windTurbulenceSize_m = scene.wind.turbulenceSize_m;
    return s;
}

namespace {

class PhysicsComputePass final : public BladeComputePass {
public:
    explicit PhysicsComputePass(GlContext& context) : pass_(context) {}

    void run(const PassInputs& in) override {
        const PhysicsSubsteps steps = physicsSubsteps(in.scene.blades.stiffness.y, in.deltaTime_s);
        const PhysicsSettings settings = physicsSettingsOf(in.scene, in.frame);
        const float start_s = in.time_s - static_cast<float>(steps.count) * steps.step_s;
        for (int k = 1; k <= steps.count; ++k) {
            const float t_s = start_s + static_cast<float>(k) * steps.step_s;
            collidersAt(in.scene, in.gpu, t_s, spheres_);
            pass_.dispatch(in.gpu.blades, in.gpu.rests, in.gpu.bladeCount, spheres_, settings,
                           steps.step_s, t_s);
        }
    }

private:
    PhysicsPass pass_;
    std::vector<CollisionSphere> spheres_;
};

}  // namespace

void collidersAt(const SceneDescription& scene, const SceneGpu& gpu, float time_s,
                 std::vector<CollisionSphere>& spheres) {
    spheres.clear();
    for (std::size_t i = 0; i < gpu.colliderSpheres.size(); ++i) {
        const glm::vec3 at = scene.colliders[i].positionAt(time_s);
        for (const CollisionSphere& s : gpu.colliderSpheres[i])
            spheres.push_back({at + s.center_m, s.radius_m});
    }
}

PhysicsSubsteps physicsSubsteps(float maxStiffness_per_s, float frameStep_s) {
    constexpr float kMaxFrame_s = 0.1f;
    constexpr float kMaxStiffnessStep = 0.5f;
    const float dt_s = std::clamp(frameStep_s, 0.f, kMaxFrame_s);
    const int count =
        std::max(1, static_cast<int>(std::ceil(maxStiffness_per_s * dt_s / kMaxStiffnessStep)));
    return {count, dt_s / static_cast<float>(count)};
}

std::unique_ptr<BladeComputePass> makePhysicsComputePass(GlContext& context) {
    return std::make_unique<PhysicsComputePass>(context);
}

void installPhysicsPass(Renderer& renderer, GlContext& context) {
    renderer.setPhysicsPass(makePhysicsComputePass(context));
}

}  // namespace meadow::runtime
