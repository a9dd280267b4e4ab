// Per-blade physics of Jahrmann & Wimmer 2017, "Responsive Real-Time Grass Rendering for General
// 3D Scenes" (I3D), Sec. 5: one function per equation, locals named after the paper's symbols.
//
// ONE TEXT FOR GPU AND CPU. shaders/physics.comp gets this file from the shader loader, and the
// CPU reference (runtime/src/physics_reference.cpp) #includes the very same file with glm in
// scope, so the oracle cannot drift from the shader. It is therefore written in the common subset
// of GLSL 4.50 and C++20: no swizzles (vec3(v) keeps xyz of a vec4), no out/inout parameters,
// float literals with an f suffix, aggregates built as Type(a, b).
//
// Blade: v0 root, v1 middle control point, v2 tip, h height, s stiffness, up the local surface
// normal; Iv1 / Iv2 the captured rest pose (BladeRestGpu), eta the collision strength.

const float kPhysicsPi = 3.14159265358979f;
// Below this length (m) a vector has no usable direction.
const float kDirectionEpsilon_m = 1e-7f;
// Eq. (12): v1 never sinks below 5 % of the height above v0.
const float kMiddleFloorFraction = 0.05f;
// Eq. (9) ff.: m = v0/4 + v1/2 + v2/4 moves by a quarter of what v2 moves (v0, v1 held), so a
// translation d of m is applied to v2 as 4 d.
const float kMidpointToTipLever = 4.0f;
// bezierArcLength: below this |Q|^2 / |P|^2 the speed |B'| is nearly constant and 3-point
// Gauss-Legendre is exact to float precision ((|Q|/|P|)^6 ~ 1e-6); above it the closed form has
// at most ~10x cancellation.
const float kNearlyStraightRatio2 = 0.01f;
// bezierArcLength: c^2 below this (t units) makes the c^2 asinh term vanish (< 1e-10).
const float kArcTinyC2 = 1e-12f;

struct BladeCurve {
    vec3 v1;
    vec3 v2;
#ifdef __cplusplus
    // GLSL builds it as BladeCurve(v1, v2); C++ before clang 16 needs the constructor for that.
    BladeCurve() = default;
    BladeCurve(vec3 a, vec3 b) : v1(a), v2(b) {}
#endif
};

vec3 safeNormalize(vec3 v) {
    float l = length(v);
    return l > kDirectionEpsilon_m ? v / l : vec3(0.0f);
}

// The blade's width direction from up and its direction angle (rad) about up: the convention of
// bladeWidthDirection() in common_blade.glsl (draw pass) and seeding.cpp, restated here in the
// GLSL/C++ subset (common_blade.glsl has out parameters, so C++ cannot compile it);
// culling_pass_GLTest.cpp holds the two against each other. Reference tangent: world +Z crossed
// with up, or +X when up is within ~26 degrees of +-Z; the angle turns it about up.
const float kReferenceAxisSwitchZ = 0.9f;
vec3 bladeWidthAxis(vec3 up, float angle) {
    vec3 axis = abs(up.z) < kReferenceAxisSwitchZ ? vec3(0.0f, 0.0f, 1.0f) : vec3(1.0f, 0.0f, 0.0f);
    vec3 t = normalize(cross(up, axis));
    vec3 b = cross(up, t);
    return cos(angle) * t + sin(angle) * b;
}

// Front direction f: perpendicular to the blade's width and to up (the blade's face normal, the
// droop direction d = cross(w, up) of seeding.cpp).
vec3 bladeFrontDirection(vec3 up, float angle) {
    return safeNormalize(cross(bladeWidthAxis(up, angle), up));
}

// Quadratic Bezier midpoint B(1/2) = v0/4 + v1/2 + v2/4 (Sec. 5.1, collision).
vec3 bezierMidpoint(vec3 v0, vec3 v1, vec3 v2) { return 0.25f * v0 + 0.5f * v1 + 0.25f * v2; }

// Recovery, Jahrmann & Wimmer 2017, Eq. (2): r = (Iv2 - v2) s, weakened while the blade is
// trampled: the factor max(1 - eta, floor) (Sec. 5.1) keeps a pressed blade down for a while.
vec3 recoveryForce(vec3 Iv2, vec3 v2, float s, float eta, float recoveryFloor) {
    return (Iv2 - v2) * s * max(1.0f - eta, recoveryFloor);
}

// Environmental gravity, Jahrmann & Wimmer 2017, Eq. (3):
//   gE = m (D.xyz/|D.xyz| D.w (1 - t) + (C.xyz - v0)/|C.xyz - v0| C.w t),
// a gravity direction D (earth) blended with a gravity centre C (a planet) by t.
vec3 environmentalGravity(PhysicsParamsGpu p, vec3 v0) {
    float m = p.gravityMix_dt.x;
    float t = p.gravityMix_dt.y;
    vec3 towardD = safeNormalize(vec3(p.gravityDirection)) * p.gravityDirection.w;
    vec3 towardC = safeNormalize(vec3(p.gravityCenter) - v0) * p.gravityCenter.w;
    return m * (towardD * (1.0f - t) + towardC * t);
}

// Front gravity, Jahrmann & Wimmer 2017, Eq. (4): gF = 1/4 |gE| f, which bends the blade over
// its front instead of only compressing it along up.
vec3 frontGravity(vec3 gE, vec3 f) { return 0.25f * length(gE) * f; }

// Total gravity, Jahrmann & Wimmer 2017, Eq. (5): g = gE + gF.
vec3 totalGravity(vec3 gE, vec3 gF) { return gE + gF; }

// Wind function wi(v0), Jahrmann & Wimmer 2017, Sec. 5.1 ("wind"): the paper leaves the function
// free; meadow sums a directional wave and a point source. Directional: travelling waves along
// the direction, amplitude in [0, A] so the wind never blows backwards.
vec3 windDirectionalWave(PhysicsParamsGpu p, vec3 v0) {
    vec3 direction = safeNormalize(vec3(p.windWave));
    float wavelength_m = max(p.windShape.x, kDirectionEpsilon_m);
    // Frequency, not period: 0 Hz is a wave that stands still (a steady breeze in its pattern).
    float frequency_hz = max(p.windShape.y, 0.0f);
    float phase = 2.0f * kPhysicsPi * (dot(direction, v0) / wavelength_m - p.gravityMix_dt.w * frequency_hz);
    return direction * p.windWave.w * (0.5f + 0.5f * sin(phase));
}

// Point source (a helicopter, a fan): radial rings travelling outwards, fading linearly to zero
// at the source radius.
vec3 windPointSource(PhysicsParamsGpu p, vec3 v0) {
    vec3 fromSource = v0 - vec3(p.windSource);
    float distance_m = length(fromSource);
    float wavelength_m = max(p.windShape.x, kDirectionEpsilon_m);
    float frequency_hz = max(p.windShape.y, 0.0f);
    float radius_m = max(p.windShape.z, kDirectionEpsilon_m);
    float falloff = max(1.0f - distance_m / radius_m, 0.0f);
    float phase = 2.0f * kPhysicsPi * (distance_m / wavelength_m - p.gravityMix_dt.w * frequency_hz);
    return safeNormalize(fromSource) * p.windSource.w * falloff * (0.5f + 0.5f * sin(phase));
}

// lowbias32 (Wellons 2018, "Prospecting for hash functions"): 32-bit integer avalanche, the same
// bits in GLSL and C++.
uint windHash(uint x) {
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// Value noise in [0, 1): a hashed value at each integer lattice point, blended with a smoothstep
// between them; `salt` picks an independent field.
float latticeValue(int x, int y, uint salt) {
    uint h = windHash(uint(x) * 0x9e3779b1u ^ windHash(uint(y) ^ salt));
    return float(h >> 8u) * (1.0f / 16777216.0f);
}

float valueNoise(vec2 q, uint salt) {
    vec2 cell = floor(q);
    vec2 f = q - cell;
    vec2 u = f * f * (vec2(3.0f) - 2.0f * f);
    int x = int(cell.x);
    int y = int(cell.y);
    float a = latticeValue(x, y, salt);
    float b = latticeValue(x + 1, y, salt);
    float c = latticeValue(x, y + 1, salt);
    float d = latticeValue(x + 1, y + 1, salt);
    return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}

// Gusts and turbulence, after Habel, Wimmer & Jeschke 2007 (Sec. 4.2: grass moved by noise that
// the wind carries over the field): gusts are patches of stronger wind along its direction,
// about the gust size across, travelling downwind at the gust speed; turbulence is a finer noise
// stirring the blades in every horizontal direction, also carried and slowly changing. The
// noise is evaluated, not read from a texture, so the CPU reference computes the same values.
vec3 windGustsAndTurbulence(PhysicsParamsGpu p, vec3 v0) {
    vec3 direction = safeNormalize(vec3(p.windWave));
    float t = p.gravityMix_dt.w;
    vec2 carried = vec2(v0.x, v0.z) - p.windShape.w * t * vec2(direction.x, direction.z);
    float gust = p.windGust.x * valueNoise(carried / max(p.windGust.y, kDirectionEpsilon_m), 1u);
    vec2 q = carried / max(p.windGust.w, kDirectionEpsilon_m) + vec2(0.37f, 0.61f) * t;
    float tx = valueNoise(q, 2u) - 0.5f;
    float tz = valueNoise(q, 3u) - 0.5f;
    return direction * gust + 2.0f * p.windGust.z * vec3(tx, 0.0f, tz);
}

vec3 windInfluence(PhysicsParamsGpu p, vec3 v0) {
    return windDirectionalWave(p, v0) + windPointSource(p, v0) + windGustsAndTurbulence(p, v0);
}

// Directional alignment, Jahrmann & Wimmer 2017, Eq. (7): fd = 1 - |wi/|wi| . (v2-v0)/|v2-v0||;
// a blade already pointing along the wind catches none of it.
float windDirectionalAlignment(vec3 wi, vec3 v0, vec3 v2) {
    return 1.0f - abs(dot(safeNormalize(wi), safeNormalize(v2 - v0)));
}

// Height ratio, Jahrmann & Wimmer 2017, Eq. (8): fr = (v2 - v0) . up / h; a blade pressed flat
// catches no wind.
float windHeightRatio(vec3 v0, vec3 v2, vec3 up, float h) { return dot(v2 - v0, up) / h; }

// Wind force, Jahrmann & Wimmer 2017, Sec. 5.1: w = wi(v0) theta, theta = fd fr.
vec3 windForce(vec3 wi, float fd, float fr) { return wi * (fd * fr); }

// Tip displacement of one step, Jahrmann & Wimmer 2017, Sec. 5.1: v2 += (r + g + w) dt.
vec3 tipDisplacement(vec3 r, vec3 g, vec3 w, float dt) { return (r + g + w) * dt; }

// Sphere collision, Jahrmann & Wimmer 2017, Eq. (9): d = min(|c - p| - r, 0) (c - p)/|c - p|
// pushes point p (v2 or the midpoint m) out of the sphere (c, r). A point exactly at c has no
// direction to leave by and is not moved.
vec3 sphereCollisionTranslation(vec3 p, vec4 sphere) {
    vec3 c = vec3(sphere);
    float r = sphere.w;
    return min(length(c - p) - r, 0.0f) * safeNormalize(c - p);
}

// Collision strength, Jahrmann & Wimmer 2017, Sec. 5.1: eta decays by a constant amount a per
// second and grows with each collision. Departure: the paper adds |d|^2 (m^2); meadow adds
// gain |d| / h, dimensionless and independent of blade size, and clamps eta to [0, 1] so the
// recovery factor max(1 - eta, floor) stays in [floor, 1].
float collisionStrength(float eta, vec3 d, float h, float a, float gain, float dt) {
    return clamp(max(eta - a * dt, 0.0f) + gain * length(d) / h, 0.0f, 1.0f);
}

// State validation 1, Jahrmann & Wimmer 2017, Eq. (10): v2 = v2 - up min(up . (v2 - v0), 0)
// keeps the tip above the local ground plane through v0.
vec3 tipAboveGround(vec3 v0, vec3 v2, vec3 up) { return v2 - up * min(dot(up, v2 - v0), 0.0f); }

// State validation 2a, Jahrmann & Wimmer 2017, Eq. (11): lproj = |v2 - v0 - up ((v2 - v0) . up)|,
// the tip's distance from v0 projected onto the ground plane.
float projectedLength(vec3 v0, vec3 v2, vec3 up) {
    vec3 d = v2 - v0;
    return length(d - up * dot(d, up));
}

// State validation 2b, Jahrmann & Wimmer 2017, Eq. (12):
//   v1 = v0 + h up max(1 - lproj/h, 0.05 max(lproj/h, 1)):
// v1 stays above v0 along up and sinks as the tip is pushed away, never below 5 % of h.
vec3 middleControlPoint(vec3 v0, vec3 up, float h, float lproj) {
    return v0 + h * up * max(1.0f - lproj / h, kMiddleFloorFraction * max(lproj / h, 1.0f));
}

// The paper's curve length estimate, Jahrmann & Wimmer 2017, Eq. (13), with degree n = 2:
//   L0 = |v2 - v0|, L1 = |v2 - v1| + |v1 - v0|, L = (2 L0 + (n - 1) L1) / (n + 1).
// It errs by ~1 % on a blade pressed flat and by up to ~8 % on a blade folded back over its root
// (v2 straight above v0, below h), which is why it is not the default (PHYSICS_LENGTH_PAPER).
float bezierLengthPaper(vec3 v0, vec3 v1, vec3 v2) {
    float n = 2.0f;
    float L0 = length(v2 - v0);
    float L1 = length(v2 - v1) + length(v1 - v0);
    return (2.0f * L0 + (n - 1.0f) * L1) / (n + 1.0f);
}

// Integral of sqrt(u^2 + c^2) du = (u sqrt(u^2 + c^2) + c^2 asinh(u / c)) / 2; asinh written as
// sign(u) log((|u| + sqrt(u^2 + c^2)) / c), which does not cancel for u << 0.
float arcPrimitive(float u, float c2) {
    float root = sqrt(u * u + c2);
    float asinhTerm = c2 > kArcTinyC2 ? sign(u) * log((abs(u) + root) / sqrt(c2)) : 0.0f;
    return 0.5f * (u * root + c2 * asinhTerm);
}

// Exact arc length of the quadratic Bezier (departure from Eq. (13), see bezierLengthPaper):
// B'(t) = 2 (P + t Q), P = v1 - v0, Q = v2 - 2 v1 + v0. With t* = -P.Q/Q.Q and c^2 the squared
// distance of the line P + tQ from 0 over Q.Q, |B'| = 2 |Q| sqrt((t - t*)^2 + c^2).
float bezierArcLength(vec3 v0, vec3 v1, vec3 v2) {
    vec3 P = v1 - v0;
    vec3 Q = v2 - 2.0f * v1 + v0;
    float PP = dot(P, P);
    float PQ = dot(P, Q);
    float QQ = dot(Q, Q);
    if (QQ <= kNearlyStraightRatio2 * PP) {
        // 3-point Gauss-Legendre on [0, 1]: nodes 1/2 -+ sqrt(3/5)/2, weights 5/18, 8/18, 5/18.
        float dt = 0.5f * sqrt(0.6f);
        return 2.0f * ((5.0f / 18.0f) * length(P + (0.5f - dt) * Q) +
                       (8.0f / 18.0f) * length(P + 0.5f * Q) +
                       (5.0f / 18.0f) * length(P + (0.5f + dt) * Q));
    }
    float tStar = -PQ / QQ;
    float c2 = max(PP - PQ * PQ / QQ, 0.0f) / QQ;
    return 2.0f * sqrt(QQ) * (arcPrimitive(1.0f - tStar, c2) - arcPrimitive(-tStar, c2));
}

// State validation 3, Jahrmann & Wimmer 2017, Eq. (13): scale the curve about v0 by r = h / L,
//   v1corr = v0 + r (v1 - v0), v2corr = v1corr + r (v2 - v1),
// so its length becomes the height (exactly, when L is the exact length: a uniform scale).
BladeCurve lengthCorrection(vec3 v0, vec3 v1, vec3 v2, float h, float L) {
    float r = h / max(L, kDirectionEpsilon_m);
    vec3 v1corr = v0 + r * (v1 - v0);
    vec3 v2corr = v1corr + r * (v2 - v1);
    return BladeCurve(v1corr, v2corr);
}

// The three validation steps, Jahrmann & Wimmer 2017, Eq. (10)-(13), in order. Departure: v1
// carries the captured rest pose's offset from Eq. (12) (Iv1 - v1(Iv2)), so a captured bend that
// Eq. (12) cannot express survives; it is zero for a blade shaped like the paper's.
BladeCurve validateBlade(vec3 v0, vec3 v2, vec3 up, float h, vec3 Iv1, vec3 Iv2, uint lengthModel) {
    vec3 v2ground = tipAboveGround(v0, v2, up);
    vec3 restOffset = Iv1 - middleControlPoint(v0, up, h, projectedLength(v0, Iv2, up));
    vec3 v1 = middleControlPoint(v0, up, h, projectedLength(v0, v2ground, up)) + restOffset;
    float L = lengthModel == PHYSICS_LENGTH_PAPER ? bezierLengthPaper(v0, v1, v2ground)
                                                  : bezierArcLength(v0, v1, v2ground);
    return lengthCorrection(v0, v1, v2ground, h, L);
}

// Everything of one step before collisions: r + g + w of Eq. (2)-(8) moves v2 by dt.
vec3 forcedTip(BladeGpu blade, BladeRestGpu rest, PhysicsParamsGpu p) {
    vec3 v0 = vec3(blade.v0_height);
    float h = blade.v0_height.w;
    vec3 v2 = vec3(blade.v2_stiffness);
    float s = blade.v2_stiffness.w;
    vec3 up = vec3(blade.up_direction);
    vec3 Iv2 = vec3(rest.restV2_eta);
    float eta = rest.restV2_eta.w;

    vec3 r = recoveryForce(Iv2, v2, s, eta, p.collision.y);
    vec3 gE = environmentalGravity(p, v0);
    vec3 gF = frontGravity(gE, bladeFrontDirection(up, blade.up_direction.w));
    vec3 g = totalGravity(gE, gF);
    vec3 wi = windInfluence(p, v0);
    vec3 w = windForce(wi, windDirectionalAlignment(wi, v0, v2), windHeightRatio(v0, v2, up, h));
    return v2 + tipDisplacement(r, g, w, p.gravityMix_dt.z);
}

// Translation of v2 by one sphere, tested at v2 and at the midpoint m (Eq. (9) ff.).
vec3 bladeSphereTranslation(vec3 v0, vec3 v1, vec3 v2, vec4 sphere) {
    vec3 m = bezierMidpoint(v0, v1, v2);
    return sphereCollisionTranslation(v2, sphere) + kMidpointToTipLever * sphereCollisionTranslation(m, sphere);
}
