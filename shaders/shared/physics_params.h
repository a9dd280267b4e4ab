// Parameters of the per-blade physics pass (Jahrmann & Wimmer 2017, Sec. 5), shared by
// shaders/physics.comp (a std140 uniform block) and the C++ CPU reference. Compiles as GLSL 4.50
// and as C++20; vec4 / uvec4 only, so std140 and the C++ layout agree.
#ifdef __cplusplus
#pragma once
#include <cstddef>

#include "blade_types.h"
namespace meadow::runtime::gpu {
#endif

// Uniform buffer binding of PhysicsParamsGpu (FRAME_UBO_BINDING is 0).
#define PHYSICS_UBO_BINDING 1

// How the validation step measures the curve length before rescaling it to the height.
#define PHYSICS_LENGTH_EXACT 0u  // closed-form arc length (default; see common_physics.glsl)
#define PHYSICS_LENGTH_PAPER 1u  // the paper's degree-2 estimate, Eq. (13) with n = 2

struct PhysicsParamsGpu {
    vec4 gravityDirection;  // xyz D (unit, world), w its acceleration (m/s^2)
    vec4 gravityCenter;     // xyz C (world, m), w the acceleration toward C (m/s^2)
    vec4 gravityMix_dt;     // x mass m (scale), y t in [0,1] (D -> C), z dt (s), w time (s)
    vec4 windWave;          // xyz wave direction (unit, world), w amplitude (m/s)
    vec4 windSource;        // xyz point source (world, m), w amplitude (m/s)
    vec4 windShape;         // x wavelength (m), y wave frequency (Hz), z source radius (m),
                            // w speed the gusts travel at along the wind (m/s)
    vec4 windGust;          // x gust amplitude (m/s), y gust size (m), z turbulence amplitude
                            // (m/s), w turbulence size (m)
    vec4 collision;         // x eta decay a (1/s), y recovery floor, z eta gain, w unused
    uvec4 counts;           // x blades, y colliders, z PHYSICS_LENGTH_*, w unused
};

#ifdef __cplusplus
static_assert(sizeof(PhysicsParamsGpu) == 144, "std140: nine 16-byte rows");
static_assert(offsetof(PhysicsParamsGpu, windGust) == 96 &&
              offsetof(PhysicsParamsGpu, collision) == 112 &&
              offsetof(PhysicsParamsGpu, counts) == 128);
}  // namespace meadow::runtime::gpu
#endif
