#include "recording_device.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace meadow::openni_driver {

namespace {

// Reported as ONI_DEVICE_PROPERTY_DRIVER_VERSION.
constexpr OniVersion kDriverVersion = {0, 1, 0, 0};

}  // namespace

RecordingDevice::RecordingDevice(std::filesystem::path folder, capture::RecordingInfo info)
    : folder_(std::move(folder)), info_(std::move(info)) {
    mode_.pixelFormat = ONI_PIXEL_FORMAT_DEPTH_1_MM;
    mode_.resolutionX = info_.intrinsics.width_px;
    mode_.resolutionY = info_.intrinsics.height_px;
    mode_.fps = static_cast<int>(std::lround(info_.frameRate_hz));
    sensor_.sensorType = ONI_SENSOR_DEPTH;
    sensor_.numSupportedVideoModes = 1;
    sensor_.pSupportedVideoModes = &mode_;
}

RecordingDevice::~RecordingDevice() {
    for (RecordingStream* stream : streams_) delete stream;
}

OniStatus RecordingDevice::getSensorInfoList(OniSensorInfo** pSensors, int* numSensors) {
    *pSensors = &sensor_;
    *numSensors = 1;
    return ONI_STATUS_OK;
}

oni::driver::StreamBase* RecordingDevice::createStream(OniSensorType sensorType) {
    if (sensorType != ONI_SENSOR_DEPTH) return nullptr;
    auto* stream = new RecordingStream(folder_, info_);
    std::lock_guard lock(mutex_);
    streams_.push_back(stream);
    return stream;
}

void RecordingDevice::destroyStream(oni::driver::StreamBase* pStream) {
    std::lock_guard lock(mutex_);
    const auto it = std::find(streams_.begin(), streams_.end(), pStream);
    if (it == streams_.end()) return;
    delete *it;
    streams_.erase(it);
}

OniBool RecordingDevice::isPropertySupported(int propertyId) {
    return propertyId == ONI_DEVICE_PROPERTY_DRIVER_VERSION ||
           propertyId == ONI_DEVICE_PROPERTY_SERIAL_NUMBER ||
           propertyId == ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION;
}

OniStatus RecordingDevice::getProperty(int propertyId, void* data, int* pDataSize) {
    if (data == nullptr || pDataSize == nullptr) return ONI_STATUS_BAD_PARAMETER;
    switch (propertyId) {
        case ONI_DEVICE_PROPERTY_DRIVER_VERSION:
            if (*pDataSize != static_cast<int>(sizeof(OniVersion))) return ONI_STATUS_BAD_PARAMETER;
            std::memcpy(data, &kDriverVersion, sizeof(OniVersion));
            return ONI_STATUS_OK;
        case ONI_DEVICE_PROPERTY_SERIAL_NUMBER: {
            // The recording's folder name, cut to the caller's buffer.
            const std::string serial = folder_.filename().string();
            if (*pDataSize <= 0) return ONI_STATUS_BAD_PARAMETER;
            const std::size_t n = std::min<std::size_t>(serial.size(), *pDataSize - 1);
            std::memcpy(data, serial.data(), n);
            static_cast<char*>(data)[n] = '\0';
            *pDataSize = static_cast<int>(n + 1);
            return ONI_STATUS_OK;
        }
        case ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION: {
            if (*pDataSize != static_cast<int>(sizeof(OniImageRegistrationMode)))
                return ONI_STATUS_BAD_PARAMETER;
            const OniImageRegistrationMode off = ONI_IMAGE_REGISTRATION_OFF;
            std::memcpy(data, &off, sizeof(off));
            return ONI_STATUS_OK;
        }
        default:
            return ONI_STATUS_NOT_SUPPORTED;
    }
}

OniStatus RecordingDevice::setProperty(int propertyId, const void* data, int dataSize) {
    if (propertyId == ONI_DEVICE_PROPERTY_IMAGE_REGISTRATION) {
        OniImageRegistrationMode mode{};
        if (data == nullptr || dataSize != static_cast<int>(sizeof(mode)))
            return ONI_STATUS_BAD_PARAMETER;
        std::memcpy(&mode, data, sizeof(mode));
        return mode == ONI_IMAGE_REGISTRATION_OFF ? ONI_STATUS_OK : ONI_STATUS_NOT_SUPPORTED;
    }
    return ONI_STATUS_NOT_SUPPORTED;
}

OniStatus RecordingDevice::tryManualTrigger() {
    std::lock_guard lock(mutex_);
    for (RecordingStream* stream : streams_) stream->trigger();
    return ONI_STATUS_OK;
}

}  // namespace meadow::openni_driver
