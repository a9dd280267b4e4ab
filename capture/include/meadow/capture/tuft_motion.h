#pragma once
// Whether the tuft held still over a run of frames.
//
// Fusing frames, readings that recur over them (recurring_readings.h) and one archetype per blade
// across groups all assume a still tuft. Sensor noise alone changes readings from frame to frame
// by the same amount whatever the frames' distance in time; a tuft that sways changes more the
// farther apart the frames are. So the test compares two shares: of the in-band readings of a
// frame, those with no reading of the same depth in the 3x3 neighbourhood of a frame nearLag
// later, and of one farLag later: the tuft moved where the second is movedRatio times the first
// and minMovedShare more, or where the first alone reaches changedEveryFrame (see
// docs/capture.md#motion-test,
// docs/measurements/motion_calibration.md).
#include <opencv2/core/mat.hpp>
#include <span>
#include <string>

#include "meadow/capture/depth_frame.h"

namespace meadow::capture {

struct MotionParams {
    int nearLag = 1;          // frames apart for the noise's own share of changed readings
    int farLag = 6;           // frames apart for the share a moving tuft adds to
    int agreement_mm = 15;    // a reading within this of one nearby is unchanged
    float movedRatio = 1.5f;  // farLag share over nearLag share from which the tuft moved
    // ...and by at least this share of the readings more farLag apart than nearLag apart. Where
    // little changes at all, a few readings drifting make a large ratio, as on a real Kinect
    // recording of a still room (see docs/measurements/motion_calibration.md).
    float minMovedShare = 0.01f;
    // A plant that changes this share of its own readings (TuftMotion::plantChanged) from one
    // frame to the next moved whatever the ratio: a plant on a turntable, or a camera carried
    // round it, changes as much one frame apart as six. Still tufts under the simulated
    // sensor's noise change up to 27 % of their band's readings (motion_calibration).
    float changedEveryFrame = 0.4f;
    // Empty when usable; otherwise what is wrong.
    [[nodiscard]] std::string problem() const;
};

struct TuftMotion {
    double nearChanged = 0.0;  // share of in-band readings changed nearLag frames later
    double farChanged = 0.0;   // ... farLag frames later
    // Of the in-band readings within the plant's own mask (tuftMotion's `plant`), the share
    // changed nearLag frames later; nearChanged when no mask was given.
    double plantChanged = 0.0;
    int readings = 0;       // in-band readings compared at nearLag
    bool measured = false;  // false: fewer than farLag + 1 frames, or no reading in the band
    // farChanged / nearChanged (1 when nothing changed at nearLag either).
    [[nodiscard]] double ratio() const;
    [[nodiscard]] bool moved(const MotionParams& params = {}) const;
    // The plant's own readings changed from one frame to the next as a turning plant's views do
    // (MotionParams::changedEveryFrame): a turntable, or a camera carried round the plant,
    // rather than a sway.
    [[nodiscard]] bool turned(const MotionParams& params = {}) const;
    // "changed readings 0.9 % one frame apart, 2.1 % six apart (2.3x)"
    [[nodiscard]] std::string summary(const MotionParams& params = {}) const;
};

// Over the readings within [nearDepth_m, farDepth_m] (the tuft's band); `plant` (frame-sized,
// may be empty): the plant's mask in the first frame, for plantChanged. Throws CaptureError for
// frames of different sizes, an empty or inverted band, or unusable params.
[[nodiscard]] TuftMotion tuftMotion(std::span<const DepthFrame> frames, float nearDepth_m,
                                    float farDepth_m, const MotionParams& params = {},
                                    const cv::Mat1b& plant = cv::Mat1b());

}  // namespace meadow::capture
