#include "openni_source.h"

#include <OpenNI.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <opencv2/core.hpp>
#include <set>

#include "meadow/capture/error.h"
#include "openni_runtime.h"

namespace meadow::capture {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kDeviceScheme = "openni://";
constexpr double kSecondsPerMicrosecond = 1e-6;
// A file being played answers within milliseconds; a live device at >= 1 fps within a second.
constexpr int kFileFrameTimeout_ms = 2000;
constexpr int kDeviceFrameTimeout_ms = 5000;
// DEPTH_100_UM stores tenths of a millimetre.
constexpr std::uint32_t kTenthsPerMillimetre = 10;
constexpr float kFallbackFrameRate_hz = 30.f;

bool endsWithOni(const std::string& text) {
    if (text.size() < 4) return false;
    std::string tail = text.substr(text.size() - 4);
    std::transform(tail.begin(), tail.end(), tail.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return tail == ".oni";
}

bool isDepthInMillimetreUnits(::openni::PixelFormat format) {
    return format == ::openni::PIXEL_FORMAT_DEPTH_1_MM ||
           format == ::openni::PIXEL_FORMAT_DEPTH_100_UM;
}

// fx = w / (2 tan(hfov / 2)): the pinhole focal length that spans the field of view.
float focalLengthFromFieldOfView_px(int size_px, float fieldOfView_rad) {
    return static_cast<float>(size_px / (2.0 * std::tan(fieldOfView_rad / 2.0)));
}

class OpenNiSource final : public DepthSource {
public:
    explicit OpenNiSource(const std::string& uri);
    ~OpenNiSource() override;
    OpenNiSource(const OpenNiSource&) = delete;
    OpenNiSource& operator=(const OpenNiSource&) = delete;
    [[nodiscard]] const RecordingInfo& info() const override { return info_; }
    std::optional<DepthFrame> next() override;

private:
    void open(const std::string& uri);
    void close();
    void openDevice(const std::string& uri);
    void chooseDepthMode();
    void readGeometry();
    [[noreturn]] void fail(const std::string& what, const std::string& todo) const;
    cv::Mat1w toMillimetres(const ::openni::VideoFrameRef& frame) const;

    // Declared first so that it outlives the stream and device below.
    std::shared_ptr<ni::Runtime> runtime_;
    ::openni::Device device_;
    ::openni::VideoStream stream_;
    std::string name_;  // "file X" / "device Y", for messages
    bool isFile_ = false;
    // Canonical path while registered in playingFiles(); released on destruction, also when
    // the constructor throws.
    struct PlayingFile {
        std::string path;
        ~PlayingFile();
    } playingFile_;
    bool mirrorInSoftware_ = false;
    int expectedFrames_ = -1;  // -1: unknown (live device, unfinished file)
    int framesRead_ = 0;
    bool ended_ = false;
    RecordingInfo info_;
};

// Files being played in this process. OpenNI2 opens a file once per process and hands the same
// player to every opener, so two sources of one file would steal each other's frames.
std::mutex& playingFilesMutex() {
    static std::mutex m;
    return m;
}
std::set<std::string>& playingFiles() {
    static std::set<std::string> files;
    return files;
}

OpenNiSource::~OpenNiSource() { close(); }

void OpenNiSource::close() {
    stream_.stop();
    stream_.destroy();
    device_.close();
}

OpenNiSource::PlayingFile::~PlayingFile() {
    if (path.empty()) return;
    std::lock_guard lock(playingFilesMutex());
    playingFiles().erase(path);
}

OpenNiSource::OpenNiSource(const std::string& uri) {
    runtime_ = ni::Runtime::acquire();
    try {
        open(uri);
    } catch (...) {
        close();  // in the safe order; members alone would delete the stream first
        throw;
    }
}

void OpenNiSource::open(const std::string& uri) {
    openDevice(uri);

    if (!device_.hasSensor(::openni::SENSOR_DEPTH))
        fail("has no depth sensor", "use a recording or device with a depth stream");
    if (stream_.create(device_, ::openni::SENSOR_DEPTH) != ::openni::STATUS_OK)
        fail("refused to create its depth stream (" + ni::lastError() + ")",
             "check the device is not in use by another program");

    if (isFile_) {
        ::openni::PlaybackControl* playback = device_.getPlaybackControl();
        if (playback == nullptr) fail("has no playback control", "re-record the file with OpenNI2");
        // Each frame once, in order, as fast as we read: no repeat, no wall-clock pacing. Speed
        // -1 is OpenNI2's "manual" mode, where the player hands over one frame per read and so
        // never drops one. seek() is avoided on purpose: it crashes Debian's file driver.
        if (playback->setRepeatEnabled(false) != ::openni::STATUS_OK ||
            playback->setSpeed(-1.f) != ::openni::STATUS_OK)
            fail("refused playback settings (" + ni::lastError() + ")",
                 "play it with NiViewer to check the file");
        const int frames = playback->getNumberOfFrames(stream_);
        // An unfinished recording says 0xFFFFFFFF (-1 as int): read until the data runs out.
        if (frames > 0 && frames < INT_MAX) expectedFrames_ = frames;
    } else {
        chooseDepthMode();
        int frames = 0;
        if (stream_.isPropertySupported(::openni::STREAM_PROPERTY_NUMBER_OF_FRAMES) &&
            stream_.getProperty(::openni::STREAM_PROPERTY_NUMBER_OF_FRAMES, &frames) ==
                ::openni::STATUS_OK &&
            frames > 0)
            expectedFrames_ = frames;  // meadow's driver says how long its recording is
    }
    readGeometry();
    if (stream_.start() != ::openni::STATUS_OK)
        fail("refused to start its depth stream (" + ni::lastError() + ")",
             "check the device is connected and not in use");
}

void OpenNiSource::openDevice(const std::string& uri) {
    std::string deviceUri;
    if (uri.rfind(kDeviceScheme, 0) == 0) {
        deviceUri = uri.substr(kDeviceScheme.size());
        name_ = deviceUri.empty() ? "the first OpenNI2 device" : "OpenNI2 device " + deviceUri;
        std::error_code ec;
        const bool isRecordingFolder =
            !deviceUri.empty() && fs::is_regular_file(fs::path(deviceUri) / "recording.json", ec);
        if (isRecordingFolder && !ni::meadowDriverInstalled())
            throw CaptureError("cannot open " + uri + ": meadow's OpenNI2 driver, which serves " +
                               "recording folders as devices, is not loaded (no " +
                               ni::kMeadowDriverFileName + " in " + ni::driverFolder().string() +
                               "); " + ni::howToLoadMeadowDriver());
    } else if (endsWithOni(uri)) {
        isFile_ = true;
        deviceUri = uri;
        name_ = "file " + uri;
        std::error_code ec;
        if (!fs::is_regular_file(uri, ec))
            throw CaptureError("cannot open " + uri + ": no such file; check the path");
        const std::string canonical = fs::weakly_canonical(uri, ec).string();
        {
            std::lock_guard lock(playingFilesMutex());
            if (!playingFiles().insert(canonical).second)
                throw CaptureError("cannot play " + uri + " twice at once: OpenNI2 shares one " +
                                   "player per file within a process; finish or close the " +
                                   "other source of it first");
        }
        playingFile_.path = canonical;
        if (!fs::is_regular_file(ni::driverFolder() / "libOniFile.so.0", ec))
            throw CaptureError("cannot play " + uri + ": OpenNI2's file driver libOniFile.so.0 " +
                               "is missing from " + ni::driverFolder().string() +
                               "; copy it there from libopenni2-0");
    } else {
        throw std::invalid_argument("openOpenNiSource: not an .oni path or openni:// URI: " + uri);
    }

    const char* target = deviceUri.empty() ? ::openni::ANY_DEVICE : deviceUri.c_str();
    if (device_.open(target) == ::openni::STATUS_OK) return;
    if (isFile_)
        throw CaptureError("cannot play " + uri + " (" + ni::lastError() +
                           "): it is not a complete .oni recording (corrupt, truncated or never "
                           "finished); record it again or check it in NiViewer");
    if (deviceUri.empty())
        throw CaptureError("no OpenNI2 device found (" + ni::lastError() +
                           "): connect a depth camera, or serve a meadow recording as a device "
                           "with " +
                           ni::kRecordingVariable + "=<folder> and meadow's driver (" +
                           ni::howToLoadMeadowDriver() + ")");
    throw CaptureError("cannot open OpenNI2 device " + deviceUri + " (" + ni::lastError() +
                       "): check it is connected and the URI is right (openni:// opens the "
                       "first device)");
}

// Live devices: keep the current mode if it is depth in (tenths of) millimetres, else switch to
// a millimetre mode of the same size. Mirroring is switched off where the device allows; where
// it does not, frames are flipped back here. (Files are never given a video mode: the file
// driver rejects it.)
void OpenNiSource::chooseDepthMode() {
    const ::openni::VideoMode current = stream_.getVideoMode();
    if (!isDepthInMillimetreUnits(current.getPixelFormat())) {
        const auto& modes = stream_.getSensorInfo().getSupportedVideoModes();
        const ::openni::VideoMode* best = nullptr;
        for (int i = 0; i < modes.getSize(); ++i) {
            const auto& mode = modes[i];
            if (mode.getPixelFormat() != ::openni::PIXEL_FORMAT_DEPTH_1_MM) continue;
            if (best == nullptr || (mode.getResolutionX() == current.getResolutionX() &&
                                    mode.getResolutionY() == current.getResolutionY()))
                best = &mode;
        }
        if (best == nullptr || stream_.setVideoMode(*best) != ::openni::STATUS_OK)
            fail("offers no depth mode in millimetres (" + ni::lastError() + ")",
                 "use a device whose OpenNI2 driver supports PIXEL_FORMAT_DEPTH_1_MM");
    }
    if (stream_.isPropertySupported(::openni::STREAM_PROPERTY_MIRRORING))
        stream_.setMirroringEnabled(false);  // may be refused; checked in readGeometry()
}

void OpenNiSource::readGeometry() {
    const ::openni::VideoMode mode = stream_.getVideoMode();
    if (!isDepthInMillimetreUnits(mode.getPixelFormat()))
        fail("delivers depth in pixel format " + std::to_string(mode.getPixelFormat()) +
                 ", not millimetres",
             "record depth as PIXEL_FORMAT_DEPTH_1_MM or DEPTH_100_UM");
    const int width_px = mode.getResolutionX();
    const int height_px = mode.getResolutionY();
    if (width_px <= 0 || height_px <= 0)
        fail(
            "reports a frame size of " + std::to_string(width_px) + "x" + std::to_string(height_px),
            "the recording or driver is broken; record again");
    const float hfov_rad = stream_.getHorizontalFieldOfView();
    const float vfov_rad = stream_.getVerticalFieldOfView();
    const auto usable = [](float fov_rad) {
        return std::isfinite(fov_rad) && fov_rad > 0.f && fov_rad < static_cast<float>(M_PI);
    };
    if (!usable(hfov_rad) || !usable(vfov_rad))
        fail("reports no usable field of view (h " + std::to_string(hfov_rad) + " rad, v " +
                 std::to_string(vfov_rad) + " rad), so its intrinsics are unknown",
             "convert it to a recording folder and give --intrinsics");

    Intrinsics k;
    k.width_px = width_px;
    k.height_px = height_px;
    k.fx_px = focalLengthFromFieldOfView_px(width_px, hfov_rad);
    k.fy_px = focalLengthFromFieldOfView_px(height_px, vfov_rad);
    k.cx_px = (width_px - 1) / 2.f;
    k.cy_px = (height_px - 1) / 2.f;
    int cropOriginX = 0, cropOriginY = 0, cropWidth = 0, cropHeight = 0;
    if (stream_.isCroppingSupported() &&
        stream_.getCropping(&cropOriginX, &cropOriginY, &cropWidth, &cropHeight) && cropWidth > 0 &&
        cropHeight > 0) {
        // A cropped stream keeps the full sensor's optics: shift the principal point.
        k.width_px = cropWidth;
        k.height_px = cropHeight;
        k.cx_px -= static_cast<float>(cropOriginX);
        k.cy_px -= static_cast<float>(cropOriginY);
    }
    mirrorInSoftware_ = stream_.isPropertySupported(::openni::STREAM_PROPERTY_MIRRORING) &&
                        stream_.getMirroringEnabled();

    const ::openni::DeviceInfo& device = device_.getDeviceInfo();
    info_.sensor = std::string("openni2:") + device.getVendor() + "/" + device.getName();
    info_.intrinsics = k;
    info_.depthUnit = DepthUnit::Millimetre;
    info_.frameCount = std::max(expectedFrames_, 0);
    info_.frameRate_hz = mode.getFps() > 0 ? static_cast<double>(mode.getFps())
                                           : static_cast<double>(kFallbackFrameRate_hz);
}

std::optional<DepthFrame> OpenNiSource::next() {
    if (ended_) return std::nullopt;
    if (expectedFrames_ >= 0 && framesRead_ >= expectedFrames_) {
        ended_ = true;
        return std::nullopt;
    }
    if (isFile_ && framesRead_ == expectedFrames_ - 1) {
        // Before asking for the last frame, let the player wrap around: after it, it then parks
        // on frame 1 waiting to be asked (which nobody does). Without repeat, Debian's file
        // driver spins at the end of the file calling into OpenNI2 and walking its stream list
        // unlocked, and tearing the stream down meanwhile can crash the process.
        device_.getPlaybackControl()->setRepeatEnabled(true);
    }
    ::openni::VideoStream* streams[] = {&stream_};
    int ready = -1;
    const int timeout_ms = isFile_ ? kFileFrameTimeout_ms : kDeviceFrameTimeout_ms;
    const ::openni::Status waited =
        ::openni::OpenNI::waitForAnyStream(streams, 1, &ready, timeout_ms);
    if (waited == ::openni::STATUS_TIME_OUT) {
        if (expectedFrames_ < 0 && isFile_) {  // unfinished file: the data simply stops
            ended_ = true;
            return std::nullopt;
        }
        if (expectedFrames_ >= 0)
            fail("stopped after " + std::to_string(framesRead_) + " of " +
                     std::to_string(expectedFrames_) + " frames",
                 "the file is damaged past that frame; record it again");
        fail("sent no frame for " + std::to_string(timeout_ms / 1000) + " s",
             "check the camera is connected and streaming");
    }
    if (waited != ::openni::STATUS_OK)
        fail("failed while waiting for a frame (" + ni::lastError() + ")",
             "check the device is still connected");
    ::openni::VideoFrameRef frame;
    if (stream_.readFrame(&frame) != ::openni::STATUS_OK || !frame.isValid())
        fail(
            "failed to deliver frame " + std::to_string(framesRead_) + " (" + ni::lastError() + ")",
            "the recording may be damaged; record it again");

    DepthFrame out;
    out.depth_mm = toMillimetres(frame);
    if (mirrorInSoftware_) cv::flip(out.depth_mm, out.depth_mm, 1);
    out.intrinsics = info_.intrinsics;
    out.timestamp_s = static_cast<double>(frame.getTimestamp()) * kSecondsPerMicrosecond;
    out.index = framesRead_++;
    return out;
}

cv::Mat1w OpenNiSource::toMillimetres(const ::openni::VideoFrameRef& frame) const {
    const int width_px = frame.getWidth();
    const int height_px = frame.getHeight();
    const int stride_bytes = frame.getStrideInBytes();
    const auto format = frame.getVideoMode().getPixelFormat();
    const std::string where = "frame " + std::to_string(framesRead_);
    if (width_px != info_.intrinsics.width_px || height_px != info_.intrinsics.height_px)
        fail(where + " is " + std::to_string(width_px) + "x" + std::to_string(height_px) +
                 " instead of " + std::to_string(info_.intrinsics.width_px) + "x" +
                 std::to_string(info_.intrinsics.height_px),
             "the stream changed size mid-way; split the recording");
    if (!isDepthInMillimetreUnits(format))
        fail(where + " has pixel format " + std::to_string(format), "record depth in millimetres");
    const std::int64_t rowBytes = static_cast<std::int64_t>(width_px) * 2;
    if (stride_bytes < rowBytes ||
        static_cast<std::int64_t>(stride_bytes) * height_px > frame.getDataSize() ||
        frame.getData() == nullptr)
        fail(where + " holds " + std::to_string(frame.getDataSize()) + " bytes, too few for " +
                 std::to_string(width_px) + "x" + std::to_string(height_px) + " depth",
             "the recording is damaged; record it again");

    cv::Mat1w depth_mm(height_px, width_px);
    const auto* bytes = static_cast<const unsigned char*>(frame.getData());
    for (int y = 0; y < height_px; ++y) {
        std::uint16_t* row = depth_mm.ptr<std::uint16_t>(y);
        std::memcpy(row, bytes + static_cast<std::ptrdiff_t>(y) * stride_bytes,
                    static_cast<std::size_t>(rowBytes));
        if (format == ::openni::PIXEL_FORMAT_DEPTH_100_UM)
            for (int x = 0; x < width_px; ++x)  // round to the nearest millimetre
                row[x] = static_cast<std::uint16_t>(
                    (static_cast<std::uint32_t>(row[x]) + kTenthsPerMillimetre / 2) /
                    kTenthsPerMillimetre);
    }
    return depth_mm;
}

void OpenNiSource::fail(const std::string& what, const std::string& todo) const {
    throw CaptureError(name_ + " " + what + ": " + todo);
}

}  // namespace

std::unique_ptr<DepthSource> openOpenNiSource(const std::string& uri) {
    return std::make_unique<OpenNiSource>(uri);
}

}  // namespace meadow::capture
