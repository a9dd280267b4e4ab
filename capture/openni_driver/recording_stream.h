#pragma once
// meadow's OpenNI2 driver: the depth stream of a meadow recording folder served as a live
// device. Frames are produced on demand: OpenNI2 asks for one (tryManualTrigger, which it sends
// whenever an application waits for or reads a frame) and the stream hands over the next frame
// of the recording. A real camera would push frames at its own pace and OpenNI2 would drop the
// ones nobody read; pulling keeps every frame of a recording, in order, for readers and for
// openni::Recorder alike. After the last frame the stream goes quiet.
#include <Driver/OniDriverAPI.h>

#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>

#include "meadow/capture/depth_source.h"

namespace meadow::openni_driver {

// Largest depth the stream reports (ONI_STREAM_PROPERTY_MAX_VALUE). openni::Recorder's 16z
// codec stores values strictly below it, so this keeps every millimetre value but 65535.
inline constexpr int kMaxDepth_mm = 65535;

class RecordingStream final : public oni::driver::StreamBase {
public:
    RecordingStream(std::filesystem::path folder, const capture::RecordingInfo& info);
    ~RecordingStream() override;

    OniStatus setProperty(int propertyId, const void* data, int dataSize) override;
    OniStatus getProperty(int propertyId, void* data, int* pDataSize) override;
    OniBool isPropertySupported(int propertyId) override;

    OniStatus start() override;
    void stop() override;

    // One frame wanted: wakes the producer unless a request is pending already.
    void trigger();

private:
    void produce();
    bool deliverNextFrame();

    const std::filesystem::path folder_;
    const capture::RecordingInfo info_;
    OniVideoMode videoMode_{};
    float hfov_rad_ = 0.f;
    float vfov_rad_ = 0.f;

    std::mutex mutex_;  // guards everything below
    std::condition_variable wake_;
    OniCropping cropping_{};
    OniBool mirroring_ = FALSE;
    bool running_ = false;
    bool triggered_ = false;
    std::unique_ptr<capture::DepthSource> source_;
    int nextFrame_ = 0;
    std::thread producer_;
};

}  // namespace meadow::openni_driver
