// meadow's OpenNI2 driver (libMeadowRecordingDevice.so.0): serves meadow recording folders as
// live OpenNI2 devices, so that OpenNI2 applications, openni::Recorder included, can read them.
//
// Devices: the folder named by MEADOW_OPENNI_RECORDING is listed when OpenNI2 starts (so
// openni:// / ANY_DEVICE opens it); any other recording folder opens by its path as URI.
// The C entry points OpenNI2 looks up are defined at the bottom of this file by hand:
// OniDriverAPI.h's ONI_EXPORT_DRIVER needs XnLib's XN_NEW, which Debian does not ship.
#include <Driver/OniDriverAPI.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "meadow/capture/depth_source.h"
#include "recording_device.h"

namespace meadow::openni_driver {

namespace fs = std::filesystem;

namespace {

constexpr const char* kRecordingVariable = "MEADOW_OPENNI_RECORDING";
constexpr const char* kVendor = "meadow";
constexpr const char* kDeviceName = "Recording";

bool looksLikeRecording(const char* uri) {
    if (uri == nullptr || *uri == '\0') return false;
    std::error_code ec;
    return fs::is_regular_file(fs::path(uri) / "recording.json", ec);
}

void copyString(char (&to)[ONI_MAX_STR], const std::string& from) {
    std::strncpy(to, from.c_str(), ONI_MAX_STR - 1);
    to[ONI_MAX_STR - 1] = '\0';
}

}  // namespace

class RecordingDriver final : public oni::driver::DriverBase {
public:
    explicit RecordingDriver(OniDriverServices* services) : DriverBase(services) {}
    ~RecordingDriver() override { shutdown(); }

    OniStatus initialize(oni::driver::DeviceConnectedCallback connected,
                         oni::driver::DeviceDisconnectedCallback disconnected,
                         oni::driver::DeviceStateChangedCallback stateChanged,
                         void* cookie) override {
        const OniStatus status =
            DriverBase::initialize(connected, disconnected, stateChanged, cookie);
        if (status != ONI_STATUS_OK) return status;
        if (const char* folder = std::getenv(kRecordingVariable);
            folder != nullptr && *folder != '\0') {
            if (looksLikeRecording(folder))
                announce(folder);
            else
                getServices().errorLoggerAppend(
                    "meadow driver: %s=%s is not a meadow recording folder (no recording.json)",
                    kRecordingVariable, folder);
        }
        return ONI_STATUS_OK;  // a driver with no device yet is still a working driver
    }

    OniStatus tryDevice(const char* uri) override {
        if (!looksLikeRecording(uri)) return ONI_STATUS_ERROR;
        return announce(uri) ? ONI_STATUS_OK : ONI_STATUS_ERROR;
    }

    oni::driver::DeviceBase* deviceOpen(const char* uri, const char* /*mode*/) override {
        if (!looksLikeRecording(uri)) {
            getServices().errorLoggerAppend("meadow driver: %s is not a meadow recording folder",
                                            uri == nullptr ? "(null)" : uri);
            return nullptr;
        }
        try {
            // meadow's own reader checks recording.json (format, version, fields) here.
            const capture::RecordingInfo info = capture::openDepthSource(uri)->info();
            auto device = std::make_unique<RecordingDevice>(fs::path(uri), info);
            std::lock_guard lock(mutex_);
            open_.push_back(std::move(device));
            return open_.back().get();
        } catch (const std::exception& e) {
            getServices().errorLoggerAppend("meadow driver: %s", e.what());
            return nullptr;
        }
    }

    void deviceClose(oni::driver::DeviceBase* device) override {
        std::lock_guard lock(mutex_);
        for (auto it = open_.begin(); it != open_.end(); ++it)
            if (it->get() == device) {
                open_.erase(it);
                return;
            }
    }

    void shutdown() override {
        std::lock_guard lock(mutex_);
        open_.clear();
    }

private:
    // Tells OpenNI2 the folder is a connected device (once per folder).
    bool announce(const char* uri) {
        if (std::strlen(uri) >= ONI_MAX_STR) {
            getServices().errorLoggerAppend(
                "meadow driver: recording path longer than %d characters: %s", ONI_MAX_STR - 1,
                uri);
            return false;
        }
        OniDeviceInfo* info = nullptr;
        {
            std::lock_guard lock(mutex_);
            for (const auto& known : announced_)
                if (std::strcmp(known->uri, uri) == 0) return true;
            announced_.push_back(std::make_unique<OniDeviceInfo>());
            info = announced_.back().get();
        }
        *info = OniDeviceInfo{};
        copyString(info->uri, uri);
        copyString(info->vendor, kVendor);
        copyString(info->name, kDeviceName);
        deviceConnected(info);
        return true;
    }

    std::mutex mutex_;
    std::vector<std::unique_ptr<OniDeviceInfo>> announced_;  // stable addresses for OpenNI2
    std::vector<std::unique_ptr<RecordingDevice>> open_;
};

}  // namespace meadow::openni_driver

// ---- The C interface OpenNI2 resolves by name in every driver -------------------------------

namespace {
using meadow::openni_driver::RecordingDriver;
using oni::driver::DeviceBase;
using oni::driver::StreamBase;
RecordingDriver* g_driver = nullptr;
}  // namespace

ONI_C_API_EXPORT void oniDriverCreate(OniDriverServices* driverServices) {
    g_driver = new RecordingDriver(driverServices);
}
ONI_C_API_EXPORT void oniDriverDestroy() {
    delete g_driver;
    g_driver = nullptr;
}
ONI_C_API_EXPORT OniStatus oniDriverInitialize(oni::driver::DeviceConnectedCallback connected,
                                               oni::driver::DeviceDisconnectedCallback disconnected,
                                               oni::driver::DeviceStateChangedCallback stateChanged,
                                               void* cookie) {
    return g_driver->initialize(connected, disconnected, stateChanged, cookie);
}
ONI_C_API_EXPORT OniStatus oniDriverTryDevice(const char* uri) { return g_driver->tryDevice(uri); }
ONI_C_API_EXPORT DeviceBase* oniDriverDeviceOpen(const char* uri, const char* mode) {
    return g_driver->deviceOpen(uri, mode);
}
ONI_C_API_EXPORT void oniDriverDeviceClose(DeviceBase* device) { g_driver->deviceClose(device); }
ONI_C_API_EXPORT OniStatus oniDriverDeviceGetSensorInfoList(DeviceBase* device,
                                                            OniSensorInfo** sensors, int* count) {
    return device->getSensorInfoList(sensors, count);
}
ONI_C_API_EXPORT StreamBase* oniDriverDeviceCreateStream(DeviceBase* device, OniSensorType type) {
    return device->createStream(type);
}
ONI_C_API_EXPORT void oniDriverDeviceDestroyStream(DeviceBase* device, StreamBase* stream) {
    device->destroyStream(stream);
}
ONI_C_API_EXPORT OniStatus oniDriverDeviceSetProperty(DeviceBase* device, int id, const void* data,
                                                      int size) {
    return device->setProperty(id, data, size);
}
ONI_C_API_EXPORT OniStatus oniDriverDeviceGetProperty(DeviceBase* device, int id, void* data,
                                                      int* size) {
    return device->getProperty(id, data, size);
}
ONI_C_API_EXPORT OniBool oniDriverDeviceIsPropertySupported(DeviceBase* device, int id) {
    return device->isPropertySupported(id);
}
ONI_C_API_EXPORT void oniDriverDeviceSetPropertyChangedCallback(
    DeviceBase* device, oni::driver::PropertyChangedCallback handler, void* cookie) {
    device->setPropertyChangedCallback(handler, cookie);
}
ONI_C_API_EXPORT void oniDriverDeviceNotifyAllProperties(DeviceBase* device) {
    device->notifyAllProperties();
}
ONI_C_API_EXPORT OniStatus oniDriverDeviceInvoke(DeviceBase* device, int id, void* data, int size) {
    return device->invoke(id, data, size);
}
ONI_C_API_EXPORT OniBool oniDriverDeviceIsCommandSupported(DeviceBase* device, int id) {
    return device->isCommandSupported(id);
}
ONI_C_API_EXPORT OniStatus oniDriverDeviceTryManualTrigger(DeviceBase* device) {
    return device->tryManualTrigger();
}
ONI_C_API_EXPORT OniBool
oniDriverDeviceIsImageRegistrationModeSupported(DeviceBase* device, OniImageRegistrationMode mode) {
    return device->isImageRegistrationModeSupported(mode);
}
ONI_C_API_EXPORT void oniDriverStreamSetServices(StreamBase* stream, OniStreamServices* services) {
    // StreamServices adds only inline helpers to OniStreamServices (OpenNI2's own drivers cast).
    stream->setServices(static_cast<oni::driver::StreamServices*>(services));
}
ONI_C_API_EXPORT OniStatus oniDriverStreamSetProperty(StreamBase* stream, int id, const void* data,
                                                      int size) {
    return stream->setProperty(id, data, size);
}
ONI_C_API_EXPORT OniStatus oniDriverStreamGetProperty(StreamBase* stream, int id, void* data,
                                                      int* size) {
    return stream->getProperty(id, data, size);
}
ONI_C_API_EXPORT OniBool oniDriverStreamIsPropertySupported(StreamBase* stream, int id) {
    return stream->isPropertySupported(id);
}
ONI_C_API_EXPORT void oniDriverStreamSetPropertyChangedCallback(
    StreamBase* stream, oni::driver::PropertyChangedCallback handler, void* cookie) {
    stream->setPropertyChangedCallback(handler, cookie);
}
ONI_C_API_EXPORT void oniDriverStreamNotifyAllProperties(StreamBase* stream) {
    stream->notifyAllProperties();
}
ONI_C_API_EXPORT OniStatus oniDriverStreamInvoke(StreamBase* stream, int id, void* data, int size) {
    return stream->invoke(id, data, size);
}
ONI_C_API_EXPORT OniBool oniDriverStreamIsCommandSupported(StreamBase* stream, int id) {
    return stream->isCommandSupported(id);
}
ONI_C_API_EXPORT OniStatus oniDriverStreamStart(StreamBase* stream) { return stream->start(); }
ONI_C_API_EXPORT void oniDriverStreamStop(StreamBase* stream) { stream->stop(); }
ONI_C_API_EXPORT int oniDriverStreamGetRequiredFrameSize(StreamBase* stream) {
    return stream->getRequiredFrameSize();
}
ONI_C_API_EXPORT void oniDriverStreamSetNewFrameCallback(StreamBase* stream,
                                                         oni::driver::NewFrameCallback handler,
                                                         void* cookie) {
    stream->setNewFrameCallback(handler, cookie);
}
ONI_C_API_EXPORT OniStatus oniDriverStreamConvertDepthToColorCoordinates(StreamBase* depth,
                                                                         StreamBase* color,
                                                                         int depthX, int depthY,
                                                                         OniDepthPixel depthZ,
                                                                         int* colorX, int* colorY) {
    return depth->convertDepthToColorCoordinates(color, depthX, depthY, depthZ, colorX, colorY);
}
ONI_C_API_EXPORT void* oniDriverEnableFrameSync(StreamBase** streams, int count) {
    return g_driver->enableFrameSync(streams, count);
}
ONI_C_API_EXPORT void oniDriverDisableFrameSync(void* group) { g_driver->disableFrameSync(group); }
