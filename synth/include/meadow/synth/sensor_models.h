#pragma once
// Depth cameras the simulated sensor can stand for: intrinsics, noise model and where their
// figures come from. docs/capture.md ("Sensor models") describes each; the Kinect v1 model is
// calibrated against a real Kinect recording (docs/measurements/sensor_calibration.md).
#include <string>

#include "meadow/capture/intrinsics.h"
#include "meadow/core/enum_names.h"
#include "meadow/synth/simulated_sensor.h"

namespace meadow::synth {

enum class SensorKind {
    KinectV1,       // structured light, PrimeSense PS1080
    KinectV2,       // time of flight
    RealSenseD435,  // active infrared stereo
};

inline constexpr EnumNames<SensorKind, 3> kSensorKindNames{{{
    {SensorKind::KinectV1, "kinect-v1"},
    {SensorKind::KinectV2, "kinect-v2"},
    {SensorKind::RealSenseD435, "realsense-d435"},
}}};

struct SensorModel {
    Intrinsics intrinsics;
    NoiseModel noise;
    std::string description;  // one line: what it is and where its figures come from
};

[[nodiscard]] SensorModel sensorModel(SensorKind kind);

// The Kinect v1 model before its calibration against the real recording: NoiseModel's defaults,
// Nguyen et al. 2012's figures with an independent displacement per edge pixel. The accuracy
// floors and the committed samples were set on it; the calibration table compares with it.
inline constexpr const char* kUncalibratedKinectV1Name = "kinect-v1-uncalibrated";
[[nodiscard]] SensorModel uncalibratedKinectV1();

}  // namespace meadow::synth
