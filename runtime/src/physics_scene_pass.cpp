#include "physics_scene_pass.h"

#include <algorithm>
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
    return s;
}

namespace {

class PhysicsComputePass final : public BladeComputePass {
public:
    explicit PhysicsComputePass(GlContext& context) : pass_(context) {}

    void run(const PassInputs& in) override {
        spheres_.clear();
        for (const ColliderDescription& c : in.scene.colliders)
            spheres_.push_back({c.center_m + c.velocity_m_s * in.time_s, c.radius_m});
        // A long hitch (a debugger, a slow first frame) must not launch the blades: the explicit
        // step is stable for s * dt < 1, so dt is capped at 1/20 s.
        constexpr float kMaxStep_s = 0.05f;
        pass_.dispatch(in.gpu.blades, in.gpu.rests, in.gpu.bladeCount, spheres_,
                       physicsSettingsOf(in.scene, in.frame), std::min(in.deltaTime_s, kMaxStep_s),
                       in.time_s);
    }

private:
    PhysicsPass pass_;
    std::vector<CollisionSphere> spheres_;
};

}  // namespace

std::unique_ptr<BladeComputePass> makePhysicsComputePass(GlContext& context) {
    return std::make_unique<PhysicsComputePass>(context);
}

void installPhysicsPass(Renderer& renderer, GlContext& context) {
    renderer.setPhysicsPass(makePhysicsComputePass(context));
}

}  // namespace meadow::runtime
