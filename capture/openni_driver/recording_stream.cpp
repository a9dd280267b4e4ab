#include "recording_stream.h"

#include <cmath>
#include <cstring>
#include <opencv2/core.hpp>

#include "meadow/capture/error.h"

namespace meadow::openni_driver {

namespace {

constexpr double kMicrosecondsPerSecond = 1e6;

// The field of view a pinhole of focal length f spans over n pixels: 2 atan(n / (2 f)).
// (OpenNI2 describes optics by field of view only; the principal point is taken as the centre.)
float fieldOfView_rad(int size_px, float focal_px) {
    return static_cast<float>(2.0 * std::atan(size_px / (2.0 * focal_px)));
}

// Copies a property value out after checking the caller's buffer is exactly its size.
template <class T>
OniStatus put(const T& value, void* data, int* pDataSize) {
    if (data == nullptr || pDataSize == nullptr || *pDataSize != static_cast<int>(sizeof(T)))
        return ONI_STATUS_BAD_PARAMETER;
    std::memcpy(data, &value, sizeof(T));
    return ONI_STATUS_OK;
}

template <class T>
bool take(const void* data, int dataSize, T& value) {
    if (data == nullptr || dataSize != static_cast<int>(sizeof(T))) return false;
    std::memcpy(&value, data, sizeof(T));
    return true;
}

}  // namespace

RecordingStream::RecordingStream(std::filesystem::path folder, const capture::RecordingInfo& info)
    : folder_(std::move(folder)), info_(info) {
    videoMode_.pixelFormat = ONI_PIXEL_FORMAT_DEPTH_1_MM;
    videoMode_.resolutionX = info.intrinsics.width_px;
    videoMode_.resolutionY = info.intrinsics.height_px;
    videoMode_.fps = static_cast<int>(std::lround(info.frameRate_hz));
    hfov_rad_ = fieldOfView_rad(info.intrinsics.width_px, info.intrinsics.fx_px);
    vfov_rad_ = fieldOfView_rad(info.intrinsics.height_px, info.intrinsics.fy_px);
    cropping_.enabled = FALSE;
    cropping_.originX = 0;
    cropping_.originY = 0;
    cropping_.width = info.intrinsics.width_px;
    cropping_.height = info.intrinsics.height_px;
}

RecordingStream::~RecordingStream() { stop(); }

OniBool RecordingStream::isPropertySupported(int propertyId) {
    switch (propertyId) {
        case ONI_STREAM_PROPERTY_VIDEO_MODE:
        case ONI_STREAM_PROPERTY_CROPPING:
        case ONI_STREAM_PROPERTY_HORIZONTAL_FOV:
        case ONI_STREAM_PROPERTY_VERTICAL_FOV:
        case ONI_STREAM_PROPERTY_MAX_VALUE:
        case ONI_STREAM_PROPERTY_MIN_VALUE:
        case ONI_STREAM_PROPERTY_STRIDE:
        case ONI_STREAM_PROPERTY_MIRRORING:
        case ONI_STREAM_PROPERTY_NUMBER_OF_FRAMES:
            return TRUE;
        default:
            return FALSE;
    }
}

OniStatus RecordingStream::getProperty(int propertyId, void* data, int* pDataSize) {
    std::lock_guard lock(mutex_);
    switch (propertyId) {
        case ONI_STREAM_PROPERTY_VIDEO_MODE:
            return put(videoMode_, data, pDataSize);
        case ONI_STREAM_PROPERTY_CROPPING:
            return put(cropping_, data, pDataSize);
        case ONI_STREAM_PROPERTY_HORIZONTAL_FOV:
            return put(hfov_rad_, data, pDataSize);
        case ONI_STREAM_PROPERTY_VERTICAL_FOV:
            return put(vfov_rad_, data, pDataSize);
        case ONI_STREAM_PROPERTY_MAX_VALUE:
            return put(kMaxDepth_mm, data, pDataSize);
        case ONI_STREAM_PROPERTY_MIN_VALUE:
            return put(0, data, pDataSize);
        case ONI_STREAM_PROPERTY_STRIDE: {
            const int width_px = cropping_.enabled ? cropping_.width : videoMode_.resolutionX;
            return put(width_px * static_cast<int>(sizeof(OniDepthPixel)), data, pDataSize);
        }
        case ONI_STREAM_PROPERTY_MIRRORING:
            return put(mirroring_, data, pDataSize);
        case ONI_STREAM_PROPERTY_NUMBER_OF_FRAMES:
            return put(info_.frameCount, data, pDataSize);
        default:
            return ONI_STATUS_NOT_SUPPORTED;
    }
}

OniStatus RecordingStream::setProperty(int propertyId, const void* data, int dataSize) {
    std::lock_guard lock(mutex_);
    switch (propertyId) {
        case ONI_STREAM_PROPERTY_VIDEO_MODE: {
            // A recording has one mode: accept it, refuse any other.
            OniVideoMode wanted{};
            if (!take(data, dataSize, wanted)) return ONI_STATUS_BAD_PARAMETER;
            const bool same = wanted.pixelFormat == videoMode_.pixelFormat &&
                              wanted.resolutionX == videoMode_.resolutionX &&
                              wanted.resolutionY == videoMode_.resolutionY &&
                              wanted.fps == videoMode_.fps;
            return same ? ONI_STATUS_OK : ONI_STATUS_NOT_SUPPORTED;
        }
        case ONI_STREAM_PROPERTY_CROPPING: {
            OniCropping wanted{};
            if (!take(data, dataSize, wanted)) return ONI_STATUS_BAD_PARAMETER;
            if (wanted.enabled &&
                (wanted.originX < 0 || wanted.originY < 0 || wanted.width <= 0 ||
                 wanted.height <= 0 || wanted.originX + wanted.width > videoMode_.resolutionX ||
                 wanted.originY + wanted.height > videoMode_.resolutionY))
                return ONI_STATUS_BAD_PARAMETER;
            if (!wanted.enabled) {
                wanted.originX = wanted.originY = 0;
                wanted.width = videoMode_.resolutionX;
                wanted.height = videoMode_.resolutionY;
            }
            cropping_ = wanted;
            return ONI_STATUS_OK;
        }
        case ONI_STREAM_PROPERTY_MIRRORING:
            return take(data, dataSize, mirroring_) ? ONI_STATUS_OK : ONI_STATUS_BAD_PARAMETER;
        default:
            return ONI_STATUS_NOT_SUPPORTED;
    }
}

OniStatus RecordingStream::start() {
    stop();
    std::unique_ptr<capture::DepthSource> source;
    try {
        // Each start plays the recording from its first frame, through meadow's own reader.
        source = capture::openDepthSource(folder_.string());
    } catch (const std::exception&) {
        return ONI_STATUS_ERROR;
    }
    std::lock_guard lock(mutex_);
    source_ = std::move(source);
    nextFrame_ = 0;
    triggered_ = false;
    running_ = true;
    producer_ = std::thread([this] { produce(); });
    return ONI_STATUS_OK;
}

void RecordingStream::stop() {
    {
        std::lock_guard lock(mutex_);
        running_ = false;
    }
    wake_.notify_all();
    if (producer_.joinable()) producer_.join();
    std::lock_guard lock(mutex_);
    source_.reset();
}

void RecordingStream::trigger() {
    {
        std::lock_guard lock(mutex_);
        triggered_ = true;
    }
    wake_.notify_all();
}

void RecordingStream::produce() {
    for (;;) {
        {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return !running_ || triggered_; });
            if (!running_) return;
            triggered_ = false;
        }
        if (!deliverNextFrame()) {
            // End of the recording (or a frame that cannot be read): go quiet like an
            // unplugged camera; the reader's timeout or frame count ends its loop.
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [this] { return !running_; });
            return;
        }
    }
}

bool RecordingStream::deliverNextFrame() {
    std::optional<capture::DepthFrame> frame;
    OniCropping cropping{};
    OniBool mirroring = FALSE;
    int index = 0;
    {
        std::lock_guard lock(mutex_);
        if (!source_) return false;
        try {
            frame = source_->next();
        } catch (const std::exception&) {
            return false;
        }
        if (!frame) return false;
        cropping = cropping_;
        mirroring = mirroring_;
        index = nextFrame_++;
    }
    cv::Mat1w depth_mm = frame->depth_mm;
    if (depth_mm.cols != videoMode_.resolutionX || depth_mm.rows != videoMode_.resolutionY)
        return false;
    if (mirroring) cv::flip(depth_mm, depth_mm, 1);  // mirror the whole image, then crop
    const cv::Mat1w out =
        depth_mm(cv::Rect(cropping.originX, cropping.originY, cropping.width, cropping.height));

    OniFrame* oniFrame = getServices().acquireFrame();
    if (oniFrame == nullptr) return false;
    const int rowBytes = out.cols * static_cast<int>(sizeof(OniDepthPixel));
    const int dataSize = rowBytes * out.rows;
    if (dataSize > oniFrame->dataSize) {
        getServices().releaseFrame(oniFrame);
        return false;
    }
    auto* bytes = static_cast<unsigned char*>(oniFrame->data);
    for (int y = 0; y < out.rows; ++y)
        std::memcpy(bytes + static_cast<std::ptrdiff_t>(y) * rowBytes, out.ptr(y),
                    static_cast<std::size_t>(rowBytes));
    oniFrame->dataSize = dataSize;
    oniFrame->sensorType = ONI_SENSOR_DEPTH;
    // Recordings keep a frame rate, not per-frame times: frame i is at i / rate.
    oniFrame->timestamp =
        static_cast<uint64_t>(std::llround(index * kMicrosecondsPerSecond / info_.frameRate_hz));
    oniFrame->frameIndex = index + 1;  // OpenNI devices count frames from 1
    oniFrame->videoMode = videoMode_;
    oniFrame->width = out.cols;
    oniFrame->height = out.rows;
    oniFrame->croppingEnabled = cropping.enabled;
    oniFrame->cropOriginX = cropping.enabled ? cropping.originX : 0;
    oniFrame->cropOriginY = cropping.enabled ? cropping.originY : 0;
    oniFrame->stride = rowBytes;
    raiseNewFrame(oniFrame);
    getServices().releaseFrame(oniFrame);
    return true;
}

}  // namespace meadow::openni_driver
