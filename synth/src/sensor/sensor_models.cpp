#include "meadow/synth/sensor_models.h"

#include <stdexcept>

namespace meadow::synth {
namespace {

// Kinect v1, calibrated against shared/data/real/oni-3dj-room on the figures of
// synth/sensor_figures.h (docs/measurements/sensor_calibration.md holds them before and after):
// - axial: Nguyen et al.'s form, refitted to the recording's temporal sigma per depth bin (the
//   least worst bin over a grid of the three coefficients; the disparity steps that quantisation
//   adds on top make up much of the sigma beyond 2 m);
// - lateral: the recording's edges move in stretches along the edge, not pixel by pixel, so the
//   displacement is a field correlated over a few pixels (a block matcher's window);
// - flying pixels: the recording's share of readings between the sides of a step.
constexpr float kV1AxialBase_m = 0.0006f;
constexpr float kV1AxialQuadratic_per_m = 0.0010f;
constexpr float kV1AxialVertex_m = 0.4f;
constexpr float kV1LateralCorrelation_px = 1.5f;
constexpr float kV1FlyingPixelRate = 0.1f;

SensorModel kinectV1() {
    SensorModel m{Intrinsics::kinectV1(), NoiseModel{}, ""};
    m.noise.axialBase_m = kV1AxialBase_m;
    m.noise.axialQuadratic_per_m = kV1AxialQuadratic_per_m;
    m.noise.axialVertex_m = kV1AxialVertex_m;
    m.noise.lateralCorrelation_px = kV1LateralCorrelation_px;
    m.noise.flyingPixelRate = kV1FlyingPixelRate;
    m.description =
        "Kinect v1 / PrimeSense PS1080, structured light, 640x480, fx 575.8 px: disparity "
        "quantised to 1/8 px over a 75 mm baseline with its projector shadow, Nguyen et al. 2012 "
        "noise form, axial sigma, edge correlation and flying pixels calibrated on a real Kinect "
        "recording (docs/measurements/sensor_calibration.md)";
    return m;
}

SensorModel kinectV2() {
    SensorModel m;
    // 512 x 424 at fx = fy ~ 365 px, a 70 x 60 deg field of view: Microsoft's specification and
    // the factory calibration libfreenect2 reads from the device (about 365 px).
    m.intrinsics = {512, 424, 365.5f, 365.5f, 255.5f, 211.5f};
    NoiseModel& n = m.noise;
    // Time of flight: no projector beside the camera to cast shadows, no disparity to quantise.
    n.shadows = false;
    n.quantisation = false;
    // Axial: Fankhauser et al. 2015 ("Kinect v2 for mobile robot navigation: evaluation and
    // modeling"), sigma_z = 1.5 - 0.5 z + 0.3 z^2 mm + 0.1 mm z^1.5 theta^2 / (pi/2 - theta)^2,
    // written in vertex form: 0.3 (z - 5/6)^2 + 1.5 - 0.3 (5/6)^2 mm. 1.3 mm at 1 m, 4.3 mm at
    // 4 m, in line with Sarbolandi et al. 2015 and Lachat et al. 2015. The angle term is applied
    // beyond 60 deg as for Kinect v1; below, it adds under 0.1 mm z^1.5.
    n.axialBase_m = 0.0012917f;
    n.axialQuadratic_per_m = 0.0003f;
    n.axialVertex_m = 0.8333333f;
    n.axialGrazing_m = 0.0001f;
    n.axialGrazingDepthPower = 1.5f;
    // Edges: each pixel integrates the light of its own footprint, with no matching window, so
    // silhouettes are sharp (0.5 px, a choice, not a published figure) and moves are per pixel.
    n.lateral_px = 0.5f;
    n.lateralCorrelation_px = 0.f;
    // Flying (mixed) pixels: a pixel whose footprint straddles an edge reads a mix of both
    // depths (Sarbolandi et al. 2015; Lachat et al. 2015). Of the two pixels beside an edge,
    // the edge crosses the footprint of one, hence a rate of one half.
    n.flyingPixels = true;
    n.flyingPixelRate = 0.5f;
    // Multipath at concave corners, off a matte wall (albedo 0.5, a choice).
    n.multipath = true;
    n.multipathAlbedo = 0.5f;
    // Working range 0.5-4.5 m (Microsoft's specification).
    n.minDepth_m = 0.5f;
    n.maxDepth_m = 4.5f;
    m.description =
        "Kinect v2, time of flight, 512x424, fx 365.5 px, 0.5-4.5 m: axial sigma of Fankhauser et "
        "al. 2015, flying pixels at edges and one-bounce multipath at concave corners (Sarbolandi "
        "et al. 2015, Lachat et al. 2015); no shadow, no quantisation; not calibrated on a "
        "recording";
    return m;
}

SensorModel realSenseD435() {
    SensorModel m;
    // 848 x 480 depth at fx = fy = 430 px: within the D400 datasheet's 87 x 58 deg depth field
    // of view (+-3 x +-1 deg) at that resolution.
    m.intrinsics = {848, 480, 430.f, 430.f, 423.5f, 239.5f};
    NoiseModel& n = m.noise;
    // Active stereo over a 50 mm baseline (datasheet). The left imager is the depth camera; what
    // the right one, at +x, cannot see reads 0: the shadow term with that baseline.
    n.baseline_m = 0.05f;
    n.shadows = true;
    // Depth RMS error = z^2 subpixel / (f b), subpixel ~0.08 px (Grunnet-Jepsen et al., "Tuning
    // depth cameras for best performance", Intel 2019; Ahn et al. 2019 measure the z^2 growth on
    // a D435): vertex form with no constant term. 3.7 mm at 1 m, 60 mm at 4 m. No published
    // grazing term. Disparity steps of 1/32 px lie far below this noise: not modelled.
    constexpr float kSubpixelRms_px = 0.08f;
    n.axialBase_m = 0.f;
    n.axialVertex_m = 0.f;
    n.axialQuadratic_per_m = kSubpixelRms_px / (m.intrinsics.fx_px * n.baseline_m);
    n.axialGrazing_m = 0.f;
    n.quantisation = false;
    // Edge fattening: the matching window spreads the nearer surface a few pixels into the
    // farther one (Grunnet-Jepsen et al.); 2 px is a choice, not a datasheet figure. Flying
    // pixels are rarer than in time of flight (a choice).
    n.edgeFattening = true;
    n.edgeFattening_px = 2.f;
    n.lateral_px = 0.5f;
    n.lateralCorrelation_px = kV1LateralCorrelation_px;  // a matching window, as for Kinect v1
    n.flyingPixelRate = 0.05f;
    // Ideal range 0.3-3 m (datasheet); readings are kept to 10 m.
    n.minDepth_m = 0.3f;
    n.maxDepth_m = 10.f;
    m.description =
        "RealSense D435, active stereo, 848x480, fx 430 px, 50 mm baseline: RMS error z^2 0.08 / "
        "(f b) (Grunnet-Jepsen et al. 2019, Ahn et al. 2019), 2 px edge fattening, stereo "
        "occlusion; not calibrated on a recording";
    return m;
}

}  // namespace

SensorModel sensorModel(SensorKind kind) {
    switch (kind) {
        case SensorKind::KinectV1:
            return kinectV1();
        case SensorKind::KinectV2:
            return kinectV2();
        case SensorKind::RealSenseD435:
            return realSenseD435();
    }
    throw std::logic_error("sensorModel: a SensorKind without a model");
}

SensorModel uncalibratedKinectV1() {
    return {Intrinsics::kinectV1(), NoiseModel{},
            "Kinect v1 before calibration: NoiseModel's defaults, Nguyen et al. 2012's figures "
            "with each edge pixel displaced on its own, flying-pixel rate 0.3 (a knob)"};
}

}  // namespace meadow::synth
