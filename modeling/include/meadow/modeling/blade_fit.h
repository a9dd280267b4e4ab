#pragma once
// From one blade's contour and depth to a blade archetype (Fan & Sheng 2017, Sec. 4.3-4.4, 5.2):
// skeleton and widths (skeleton.h), refined knots (skeleton_refiner.h), a quadratic Bezier spine
// fitted by least squares with parameter correction, expressed in archetype.h's blade-local frame,
// a width profile over normalised arc length, and the nearest analytic shape of Jahrmann &
// Wimmer 2017. Every fit error is recorded in Archetype::fit.
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "meadow/capture/blade_contour.h"
#include "meadow/capture/depth_frame.h"
#include "meadow/modeling/archetype.h"
#include "meadow/modeling/blade_root.h"
#include "meadow/modeling/blade_tip.h"
#include "meadow/modeling/chain_simulation.h"
#include "meadow/modeling/skeleton.h"
#include "meadow/modeling/skeleton_refiner.h"

namespace meadow::modeling {

// ---- Spine (blade_fit_spine.cpp) ----------------------------------------------------------
struct SpineFit {
    QuadraticBezier spine_m;
    std::vector<float> t;  // parameter of each input point's closest spine point
    float rms_m = 0.f;     // RMS distance of the points to the spine (weighted; weight 0 left out)
    float max_m = 0.f;
};
// Least-squares middle control point with v0 and v2 fixed, for given parameters t_j:
//   v1 = sum_j w_j b_j (P_j - (1 - t_j)^2 v0 - t_j^2 v2) / sum_j w_j b_j^2,  b_j = 2 (1 - t_j) t_j,
// with weights w_j (empty: all 1), as fitQuadraticBezier's.
glm::vec3 leastSquaresMiddleControlPoint(const std::vector<glm::vec3>& points,
                                         const std::vector<float>& t, const glm::vec3& v0,
                                         const glm::vec3& v2,
                                         const std::vector<float>& weights = {});
// Which control points the spine fit moves. AtEndPoints: v0 = points.front() and v2 =
// points.back(), the closed form's setting. RootAtFirstPoint: v2 is fitted with v1 as well, the
// last point held at t = 1 as one residual among all, so the tip's position follows the whole
// skeleton's shape instead of resting on its least certain point (a tip 1-3 px wide). Fitted: v0
// too, the first point held at t = 0 the same way: a tuft's one base point is not every blade's
// root (bases lie millimetres apart), so it counts as one observation of where the blade starts.
enum class SpineEnds { AtEndPoints, RootAtFirstPoint, Fitted };
// Fits a quadratic Bezier: chord-length parameters, v0 and v2 at the first and last points and
// the closed-form v1, then alternately Newton steps per point on f(t) = (B(t) - P) . B'(t)
// (parameter correction, Hoschek 1988) and a tangent-distance Gauss-Newton update of the control
// points `ends` leaves free (see blade_fit_spine.cpp). `weights` (one per point, >= 0; empty: all
// 1) scale each point's residual: 0 leaves a point out of the fit, though it still gets its
// parameter t. Requires >= 3 points.
SpineFit fitQuadraticBezier(const std::vector<glm::vec3>& points_m, int iterations = 20,
                            SpineEnds ends = SpineEnds::AtEndPoints,
                            const std::vector<float>& weights = {});

// ---- Blade-local frame (blade_fit_frame.cpp) ------------------------------------------------
// local = localFromCamera * (camera - origin_m). +Y along the spine's base tangent, +X toward the
// tip's offset from that line (the bend), +Z = X x Y. A straight spine takes X from
// acrossHint (the blade's width direction in camera space) or, failing that, any perpendicular.
struct BladeFrame {
    glm::vec3 origin_m{0.f};
    glm::mat3 localFromCamera{1.f};
    [[nodiscard]] glm::vec3 toLocal(const glm::vec3& camera_m) const;
    [[nodiscard]] glm::vec3 toCamera(const glm::vec3& local_m) const;
};
BladeFrame bladeLocalFrame(const QuadraticBezier& spineCamera_m, const glm::vec3& acrossHint);

// ---- Width profile (blade_fit_width.cpp) --------------------------------------------------
// Piecewise-linear profile with `samples` evenly spaced values (archetype.h's WidthProfile),
// least squares against measured widths at arc-length fractions s (hat-function basis, with a
// small second-difference penalty so that a sample with no measurement near it is interpolated).
// Widths are clamped to >= 0. Requires samples >= 2 and s, width_m of the same non-zero size.
WidthProfile fitWidthProfile(const std::vector<float>& s, const std::vector<float>& width_m,
                             int samples);
// Mean |profile(s_j) - width_j|.
float widthProfileMae_m(const WidthProfile& profile, const std::vector<float>& s,
                        const std::vector<float>& width_m);

// ---- Nearest analytic shape (blade_fit_shape.cpp) -----------------------------------------
// Width of Jahrmann & Wimmer 2017's analytic blade shapes (Sec. 6.2) as a fraction of the base
// width at height fraction v: quad 1; triangle 1 - v; quadratic 1 - v^2; triangle-tip 1 below
// tau, then linear to 0 at the tip. (They parameterise by the Bezier parameter; here v is the
// arc-length fraction, which is what WidthProfile is sampled on.)
float analyticShapeWidthFraction(AnalyticShape shape, float v, float tau);
struct ShapeFit {
    AnalyticShape shape = AnalyticShape::Quad;
    float baseWidth_m = 0.f;  // least-squares scale of the shape
    float tau = 0.5f;
    float error_m = 0.f;  // mean |shape - profile| over the profile's samples
};
ShapeFit nearestAnalyticShape(const WidthProfile& profile);

// ---- Twist (blade_fit_twist.cpp) ---------------------------------------------------------
// The face's turn about the spine, from the depth across the blade (Skeleton::acrossStep_m). At
// each read point, in the blade-local frame, the angle of the across step about the spine
// tangent T, from the ribbon's width direction W = normalize(T x Z) toward T x W (the sense of
// blade_mesh.h's twist); a line through the angles over arc-length fraction s, fitted again
// without outliers, gives the tilt at the base and the twist at the tip. Read only over enough
// of the blade (thin blades, a few pixels wide, are not); a slope within two standard errors of
// zero is no twist.
struct TwistFit {
    bool measured = false;
    float baseTilt_rad = 0.f;    // the line at s = 0: the base's turn off the frame's face plane
    float twistAtTip_rad = 0.f;  // the line's rise from s = 0 to 1; 0 when not significant
    float rms_rad = 0.f;         // residual of the points kept
    int points = 0;              // points kept
    // Per skeleton point, the share of the fitted width direction that faces the camera (across
    // the viewing ray), at least 0.35; all 1 when not measured. The contour shows width x facing.
    std::vector<float> facing;
};
// `t`: each skeleton point's parameter on the spine; `s`: its arc-length fraction.
TwistFit fitTwist(const Skeleton& skeleton, const BladeFrame& frame,
                  const QuadraticBezier& localSpine, const std::vector<float>& t,
                  const std::vector<float>& s);

// ---- The whole fit (blade_fit.cpp) --------------------------------------------------------
struct BladeFitParams {
    SkeletonParams skeleton;
    int spineIterations = 20;
    // Both ends fitted (see SpineEnds): the skeleton's first point is the tuft's base, its last
    // the end of a thin tip or of the tip extension.
    SpineEnds spineEnds = SpineEnds::Fitted;
    // The skeleton's added pieces, the straight root piece down to the tuft's base (blade_root.h)
    // and the straight tip extension (blade_tip.h), are guesses, not readings: when false their
    // inner points are left out of the spine fit: their ends, the tuft's base and the
    // extension's end, still count, and the shape between comes from what was seen.
    bool fitSpineToAddedPieces = false;
    // Width profile: `widthSamples` values, or, when widthTolerance_m > 0, the fewest (>= 2, <=
    // widthSamples) whose mean absolute error against the measured widths is within tolerance.
    int widthSamples = 16;
    float widthTolerance_m = 0.f;
    // Refined knot count (Fan & Sheng 2017, Algorithm 1); 0 skips refining. When
    // knotTolerance_m > 0 it is the most knots kept: a binary search over the count (>= 2) keeps
    // the fewest it finds whose polyline stays within the tolerance of every skeleton knot in
    // every simulated frame (maxDeviation_m), or refinedKnots when no count it tries does.
    int refinedKnots = 16;
    float knotTolerance_m = 0.f;
    RefinerParams refiner;
    ChainSimulationParams simulation;  // up and gravity are overridden to the blade-local +Y
    RootParams root;                   // rooting at the tuft's base (fitSegmentedBlade only)
    TipParams tip;                     // continuing past the visible tip (fitSegmentedBlade only)

    // One user tolerance (`meadow capture --tolerance-mm`) for both: the width profile's mean
    // error and the refined knots' deviation. A tolerance <= 0 leaves both off.
    void setTolerance_m(float tolerance_m) {
        const float t = tolerance_m > 0.f ? tolerance_m : 0.f;
        widthTolerance_m = t;
        knotTolerance_m = t;
    }
};

struct BladeFit {
    Archetype archetype;            // blade-local frame
    QuadraticBezier spineCamera_m;  // the same spine in camera space
    BladeFrame frame;
    Skeleton skeleton;
};

// Fits an archetype to a skeleton already lifted to 3D. `mask` may be empty (no DT width check);
// its pixel (0, 0) is frame pixel maskOrigin_px (capture::BladeContour::maskOrigin_px).
BladeFit fitArchetype(const Skeleton& skeleton, const BladeFitParams& params = {},
                      const Source& source = {}, const cv::Mat1b& mask = {},
                      const capture::Intrinsics* intrinsics = nullptr,
                      cv::Point maskOrigin_px = {0, 0});
// Contour + depth to archetype: extractSkeleton then fitArchetype. Throws ModelingError when the
// blade cannot be fitted (no depth, degenerate skeleton).
BladeFit fitBlade(const capture::BladeContour& blade, const capture::DepthFrame& frame,
                  const BladeFitParams& params = {}, const Source& source = {});
// The skeleton of segmentation.blades[bladeIndex] as capture fits it: extractSkeleton, then, when
// params.tip.enabled, extendSkeletonTip (blade_tip.h), then, when params.root.enabled,
// rootSkeleton at its cluster's base (blade_root.h; a blade whose base cannot be found or is
// refused stays unrooted, with Skeleton::baseNotRooted set and a reason; a leaf that leaves a
// stem, leavesAStem, starts at its own base and is not rooted). Throws ModelingError
// when the blade has no valid depth.
Skeleton segmentedBladeSkeleton(const capture::Segmentation& segmentation, std::size_t bladeIndex,
                                const capture::DepthFrame& frame,
                                const BladeFitParams& params = {});
// segmentedBladeSkeleton, then fitArchetype. Throws ModelingError as fitBlade does.
BladeFit fitSegmentedBlade(const capture::Segmentation& segmentation, std::size_t bladeIndex,
                           const capture::DepthFrame& frame, const BladeFitParams& params = {},
                           const Source& source = {});

}  // namespace meadow::modeling
