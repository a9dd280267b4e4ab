#pragma once
// Settings of the per-blade culling (Jahrmann & Wimmer 2017, Sec. 5.2) as a user sets them; the
// culling pass packs them, with the frame's camera, into shaders/shared/cull_params.h.
namespace meadow::runtime {

struct CullSettings {
    bool orientation = true;  // Eq. (14): blades seen edge-on
    bool frustum = true;      // patch bounds, then v0 / midpoint / v2 of each blade
    bool distance = true;     // Eq. (15): distance levels by index within the patch
    bool occlusion = true;    // against the opaque depth pre-pass (skipped without one)

    float orientationThreshold = 0.97f;  // |dir_c . dir_b| above this culls (the paper: 0.9)
    float frustumTolerance = 0.1f;       // NDC units the frustum is widened by for blades
    float maxDistance_m = 100.f;         // d_max of Eq. (15): nothing is drawn beyond it
    unsigned distanceLevels = 4;         // n of Eq. (15)
    float occlusionBias_m = 0.05f;       // a point must be this far behind the opaque depth
};

class GlContext;
class Renderer;

// Plugs the GPU culling pass (cull.comp) into `renderer`: the frame's camera, the scene's
// culling settings and the opaque depth pre-pass decide which blades are drawn. Throws
// RuntimeError when the shader does not compile.
void installCullingPass(Renderer& renderer, GlContext& context);

}  // namespace meadow::runtime
