#pragma once
// A blade archetype: the product of capture and the input of the renderer.
//
// Blade-local frame (metres): v0 at the origin, +Y up along the base direction, the blade's face
// approximately in the XY plane (face normal +Z), the spine bending within that plane toward +X
// (a captured spine may carry a small Z component from depth). The width at arc-length fraction
// s is measured in the face plane, perpendicular to the spine's tangent.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "meadow/core/enum_names.h"
#include "meadow/modeling/quadratic_bezier.h"

namespace meadow::modeling {

// Analytic blade shapes of Jahrmann & Wimmer 2017, Sec. 6.2 (their Fig. 6). Quadratic is
// meadow's symmetric variant (tip on the spine); OneSidedQuadratic is the paper's own quadratic,
// one edge straight and the other curving in to meet it at the tip. Capture picks the nearest
// of the symmetric ones; OneSidedQuadratic is for authored archetypes and scene overrides.
enum class AnalyticShape { Quad, Triangle, Quadratic, TriangleTip, OneSidedQuadratic };
inline constexpr EnumNames<AnalyticShape, 5> kAnalyticShapeNames{{{
    {AnalyticShape::Quad, "quad"},
    {AnalyticShape::Triangle, "triangle"},
    {AnalyticShape::Quadratic, "quadratic"},
    {AnalyticShape::TriangleTip, "triangle-tip"},
    {AnalyticShape::OneSidedQuadratic, "one-sided-quadratic"},
}}};
inline std::string toString(AnalyticShape shape) {
    return std::string(kAnalyticShapeNames.name(shape));
}

struct WidthProfile {
    // Full width (m) at evenly spaced arc-length fractions s_i = i / (n - 1), s = 0 at the base,
    // s = 1 at the tip; n >= 2. Linear in between.
    std::vector<float> width_m;

    [[nodiscard]] float at(float s) const;  // linear interpolation, s clamped to [0, 1]
    [[nodiscard]] float maxWidth_m() const;
};

// How well the archetype matches the blade it was fitted to (blade_fit.h fills it in). Zero means
// "not measured" for an archetype that was authored rather than captured.
struct FitReport {
    float spineRms_mm = 0.f;       // RMS distance of the 3D skeleton points to the fitted spine
    float spineMax_mm = 0.f;       // largest such distance
    float widthMae_mm = 0.f;       // mean |profile - measured width| over the skeleton samples
    float widthMax_mm = 0.f;       // largest such difference
    float shapeError_mm = 0.f;     // mean |nearest analytic shape - width profile|
    float widthCheckMae_mm = 0.f;  // mean |2 x distance transform - matched width| (independent)
    float sideLengthRatio = 1.f;   // longer contour side / shorter side (1 = symmetric)
    bool asymmetric = false;       // the symmetric match is not trustworthy for this blade
    int skeletonPoints = 0;        // matched contour pairs behind the fit
    // Rooting at the tuft's base (blade_root.h): length of the straight piece from the segmented
    // base down to the cluster's base point (0: not rooted); baseNotRooted: rooting was asked
    // for and refused (the base is too far from the blade, or has no depth).
    float baseExtension_mm = 0.f;
    bool baseNotRooted = false;
    // Tip extension (blade_tip.h): length of the straight piece added past the visible tip, where
    // the tapering width's trend reaches zero (0: not extended).
    float tipExtension_mm = 0.f;
    // Twist (blade_fit.h, fitTwist): points read across the blade behind it (0: not measured),
    // and the base's tilt off the face plane the frame assumed (-90 to 90 deg: a ribbon turned a
    // half turn is the same ribbon); widths are scaled back up by how much of the face turned
    // away from the camera.
    int twistPoints = 0;
    float baseTilt_deg = 0.f;
};

// One observation of a blade: the first frame of the fused group that saw it, and the blade's id
// in that group's segmentation.
struct BladeSighting {
    int frame = -1;
    int bladeId = 0;
};

// Where an archetype came from, so a library entry can be traced back to its capture.
struct Source {
    std::string recording;  // recording folder / file name as given to capture
    int frame = -1;         // frame index in that recording (-1: unknown / authored)
    int bladeId = 0;        // BladeContour::id within that frame
    // The segmenter's flags on the blade, and the fit's too-short-for-its-width, one reason line
    // each ("too-thin: mean width ..."): empty for a blade both vouched for; capture models
    // flagged ones only with --keep-flagged.
    std::vector<std::string> flags;
    // Every observation the archetype was fitted to, the first being (frame, bladeId): capture
    // fits a blade seen in several fused groups once, to the mean of its skeletons
    // (blade_tracks.h). Empty for an authored archetype.
    std::vector<BladeSighting> seenIn;
    // Other views of the same leaf of a turning plant, whose archetypes lay along this one and
    // came out shorter: left out of the library for this one (view_joining.h). Empty otherwise.
    std::vector<BladeSighting> alsoSeenIn{};
    // Where the blade stood: camera = cameraFromBlade * blade-local (rigid, metres, the
    // recording's camera space). Unplaced for an authored archetype.
    bool placed = false;
    glm::mat4 cameraFromBlade{1.f};
};

// One full turn about the spine from base to tip is already more than any leaf shows: a library
// holding more has another unit (degrees for radians), and a fit reading more read noise.
inline constexpr float kMaxTwistAtTip_rad = 6.2831853f;

struct Archetype {
    std::string name;
    QuadraticBezier spine_m;  // blade-local frame above
    WidthProfile width;
    AnalyticShape nearestShape = AnalyticShape::Quadratic;
    float tau = 0.5f;  // triangle-tip parameter (fraction of height where the tip begins)
    // Share of the width on the blade's left side of the spine (local -X, away from the bend):
    // 0.5 is symmetric, 0.3 puts 30 % left and 70 % right. In [0, 1].
    float leftWidthFraction = 0.5f;
    // Rotation of the width direction about the spine tangent at the tip (radians, right-handed
    // about the tangent), growing linearly with arc length from 0 at the base. At most
    // kMaxTwistAtTip_rad either way.
    float twistAtTip_rad = 0.f;
    FitReport fit;
    Source source;
    // Refined skeleton knots (Fan & Sheng 2017, Algorithm 1), blade-local frame, base to tip.
    std::vector<glm::vec3> knots_m;

    // Arc length of the spine (the blade's height when straightened).
    [[nodiscard]] float height_m() const { return spine_m.length(); }
};

}  // namespace meadow::modeling
