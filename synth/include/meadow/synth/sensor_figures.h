#pragma once
// Figures that say how a depth sensor behaves on a still scene over a run of frames, measured the
// same way on a real recording and on the simulated sensor, so that one can be calibrated against
// the other (docs/capture.md, "Sensor models"; the sensor_calibration bench writes them into
// docs/measurements/sensor_calibration.md and a synth test holds the Kinect v1 model to them).
//
// Every figure starts from the *reference* image: per pixel, the median of the frames' readings
// where at least half the frames read it, else nothing. A *depth step* is a pair of 4-neighbours
// whose reference depths differ by more than FigureOptions::step_mm; it lies between them.
//
//   temporal sigma  per depth bin: the RMS over the bin's pixels of each pixel's sample standard
//                   deviation over the frames (n - 1), each scaled by (middle / z)^2 to the
//                   bin's middle depth (sigma grows with z^2), taken over pixels read in every
//                   frame and at least edgeMargin_px from a reading that is missing in some frame
//                   and from a depth edge of the reference (a jump of over 3 % of the depth);
//   mixed share     over the readings of pixels within zone_px of a depth step: the share that
//                   lie more than mixedSigmas temporal sigmas (the figure above, at the side's
//                   depth) from both sides of the step. A side's depth is the median of what the
//                   two pixels just beyond the zone read; steps whose sides' bands overlap
//                   (nothing could read between them) are left out;
//   edge run length along chains of depth steps (steps in consecutive rows, or columns, within
//                   1 px of one another, the near side on the same side), per frame: the edge's
//                   displacement from its mean over the frames, measured as the count of pixels
//                   across the step (zone and side pixels) that read nearer the near side than
//                   the far one, minus its mean. The figure is the mean length, in pixels along
//                   the edge, of the runs of consecutive steps displaced the same way; a step
//                   with no displacement ends a run and starts none. An edge whose pixels each
//                   move on their own gives runs of about 1.5-2 px; one that moves in stretches
//                   gives longer ones.
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "meadow/synth/labelled_mesh.h"
#include "meadow/synth/simulated_sensor.h"

namespace meadow::synth {

struct FigureOptions {
    float binWidth_m = 0.5f;  // temporal sigma's depth bins, from nearest_m to farthest_m
    float nearest_m = 0.5f;
    float farthest_m = 4.5f;
    long minBinPixels = 500;  // a bin with fewer pixels has no figure
    int edgeMargin_px = 3;
    float step_mm = 50.f;
    int zone_px = 2;
    float mixedSigmas = 3.f;
    int minEdgeLength_px = 8;  // shorter chains of steps give no runs
};

struct DepthBinSigma {
    float from_m = 0.f;
    float to_m = 0.f;
    double sigma_mm = 0.0;
    long pixels = 0;
};

struct SensorFigures {
    std::vector<DepthBinSigma> temporalSigma;  // only bins with minBinPixels
    double mixedShare = 0.0;
    long zoneReadings = 0;  // readings the mixed share was taken over
    double edgeRunLength_px = 0.0;
    long edgeRuns = 0;   // runs the length was taken over
    long edgeSteps = 0;  // steps on chains long enough
};

// Precondition: at least two frames, all of one size. Throws std::invalid_argument otherwise.
[[nodiscard]] SensorFigures measureSensorFigures(const std::vector<cv::Mat1w>& frames_mm,
                                                 const FigureOptions& options = {});

// The synthetic counterpart of shared/data/real/oni-3dj-room: a room of planes and boxes seen from
// 0.6 to 4.5 m (floor, ceiling, walls, furniture-like boxes giving depth steps of 0.1-3 m), in
// camera space, for a camera about 1 m above the floor looking level.
[[nodiscard]] std::vector<LabelledMesh> calibrationRoom();

// `count` frames of a still scene, frame i drawn with seed + i.
[[nodiscard]] std::vector<cv::Mat1w> renderStillFrames(const SimulatedSensor& sensor,
                                                       const std::vector<LabelledMesh>& scene,
                                                       int count, std::uint64_t seed);

}  // namespace meadow::synth
