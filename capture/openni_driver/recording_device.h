#pragma once
// meadow's OpenNI2 driver: a meadow recording folder (recording.json + depth/NNNNNN.png) seen by
// OpenNI2 as a device with one depth sensor. Its URI is the folder path.
#include <Driver/OniDriverAPI.h>

#include <filesystem>
#include <mutex>
#include <vector>

#include "meadow/capture/recording_info.h"
#include "recording_stream.h"

namespace meadow::openni_driver {

class RecordingDevice final : public oni::driver::DeviceBase {
public:
    RecordingDevice(std::filesystem::path folder, capture::RecordingInfo info);
    ~RecordingDevice() override;

    OniStatus getSensorInfoList(OniSensorInfo** pSensors, int* numSensors) override;
    oni::driver::StreamBase* createStream(OniSensorType sensorType) override;
    void destroyStream(oni::driver::StreamBase* pStream) override;

    OniStatus getProperty(int propertyId, void* data, int* pDataSize) override;
    OniStatus setProperty(int propertyId, const void* data, int dataSize) override;
    OniBool isPropertySupported(int propertyId) override;
    OniStatus tryManualTrigger() override;

private:
    const std::filesystem::path folder_;
    const capture::RecordingInfo info_;
    OniVideoMode mode_{};
    OniSensorInfo sensor_{};
    std::mutex mutex_;
    std::vector<RecordingStream*> streams_;  // owned; OpenNI2 destroys them via destroyStream
};

}  // namespace meadow::openni_driver
