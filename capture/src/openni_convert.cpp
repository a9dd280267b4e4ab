#include "openni_convert.h"

#include <OpenNI.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <climits>
#include <cstring>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <string>
#include <system_error>
#include <thread>

#include "meadow/capture/depth_source.h"
#include "meadow/capture/error.h"
#include "meadow/capture/recording.h"
#include "meadow/core/staged_folder.h"
#include "meadow/core/temporaries.h"
#include "openni_runtime.h"
#include "openni_source.h"

namespace meadow::capture::ni {

namespace fs = std::filesystem;

namespace {

// A served recording hands over a frame within milliseconds of being asked.
constexpr int kFrameTimeout_ms = 5000;
// openni::Recorder's 16z codec stores depth strictly below the stream's maximum (65535).
constexpr double kLargestStorableDepth_mm = 65534;
// Pauses between starting openni::Recorder and the first frame, one per try (see recordOnce).
constexpr std::chrono::milliseconds kRecorderStartups[] = {std::chrono::milliseconds(100),
                                                           std::chrono::milliseconds(500),
                                                           std::chrono::milliseconds(2000)};

// "<path>.tmp.<pid>.oni" beside `path` (OpenNI2's recorder wants the extension): removed on
// destruction or an interruption unless committed.
class TemporaryOni {
public:
    explicit TemporaryOni(const fs::path& path) : path_(temporaryFor(path, ".oni")) {
        sweepStaleTemporaries(path);
        registerTemporary(path_);
    }
    TemporaryOni(const TemporaryOni&) = delete;
    TemporaryOni& operator=(const TemporaryOni&) = delete;
    ~TemporaryOni() {
        if (path_.empty()) return;
        std::error_code ignored;
        fs::remove_all(path_, ignored);
        unregisterTemporary(path_);
    }
    [[nodiscard]] const fs::path& path() const { return path_; }
    // Renames the temporary over `target`; it is then no longer removed.
    void commitTo(const fs::path& target) {
        std::error_code ec;
        fs::rename(path_, target, ec);
        if (ec)
            throw CaptureError("cannot rename " + path_.string() + " to " + target.string() + " (" +
                               ec.message() + "): check permissions on the folder");
        unregisterTemporary(path_);
        path_.clear();
    }

private:
    fs::path path_;
};

// OpenNI2's recorder crashes on a path it cannot create: try creating it first, ourselves.
void checkWritable(const fs::path& file, const fs::path& target) {
    {
        std::ofstream probe(file, std::ios::binary | std::ios::trunc);
        if (!probe)
            throw CaptureError("cannot write " + target.string() + " (" + std::strerror(errno) +
                               "): check the folder exists and is writable");
    }
    std::error_code ignored;
    fs::remove(file, ignored);
}

void createParentFolder(const fs::path& path) {
    const fs::path parent = path.parent_path();
    if (parent.empty()) return;
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec)
        throw CaptureError("cannot create folder " + parent.string() + " for " + path.string() +
                           " (" + ec.message() + "): check the path and permissions");
}

// Frames an .oni file says it holds, or -1 when it cannot be opened or does not say.
int framesInOniFile(const fs::path& oniPath) {
    ::openni::Device device;
    if (device.open(oniPath.c_str()) != ::openni::STATUS_OK) return -1;
    ::openni::VideoStream stream;
    if (stream.create(device, ::openni::SENSOR_DEPTH) != ::openni::STATUS_OK) return -1;
    ::openni::PlaybackControl* playback = device.getPlaybackControl();
    if (playback == nullptr) return -1;
    const int frames = playback->getNumberOfFrames(stream);
    // Debian's file driver walks its stream list without a lock while no stream has started,
    // and can crash when one is deleted meanwhile; a started stream in manual mode parks its
    // player thread on a wait instead.
    playback->setRepeatEnabled(false);
    playback->setSpeed(-1.f);
    stream.start();
    stream.stop();
    return frames;
}

// Serves `uri` through meadow's driver into a fresh .oni file at `oniPath`; returns the frames
// the finished file holds.
int recordOnce(const std::string& uri, const fs::path& oniPath, const RecordingInfo& info,
               std::chrono::milliseconds recorderStartup, const FrameProgress& progress) {
    {
        ::openni::Device device;
        if (device.open(uri.c_str()) != ::openni::STATUS_OK)
            throw CaptureError("meadow's OpenNI2 driver cannot serve " + uri + " (" + lastError() +
                               "): check the recording's recording.json and depth/ PNGs");
        ::openni::VideoStream stream;
        if (stream.create(device, ::openni::SENSOR_DEPTH) != ::openni::STATUS_OK)
            throw CaptureError("meadow's OpenNI2 driver gave no depth stream for " + uri + " (" +
                               lastError() + ")");
        ::openni::Recorder recorder;
        if (recorder.create(oniPath.c_str()) != ::openni::STATUS_OK)
            throw CaptureError("cannot write " + oniPath.string() + " (" + lastError() +
                               "): check the folder exists and is writable");
        if (recorder.attach(stream, /*allowLossyCompression=*/false) != ::openni::STATUS_OK ||
            recorder.start() != ::openni::STATUS_OK)
            throw CaptureError("OpenNI2's recorder refused the depth stream of " + uri + " (" +
                               lastError() + ")");
        // openni::Recorder starts on its own thread and silently drops frames that arrive
        // before it has; there is no way to ask whether it has, so give it time (the caller
        // checks the result and tries again with more).
        std::this_thread::sleep_for(recorderStartup);
        if (stream.start() != ::openni::STATUS_OK)
            throw CaptureError("meadow's OpenNI2 driver cannot start " + uri + " (" + lastError() +
                               ")");

        // The recorder keeps every frame the driver sends; reading them here is what asks the
        // driver for the next one (it serves frames on demand) and checks what goes in.
        ::openni::VideoStream* streams[] = {&stream};
        for (int i = 0; i < info.frameCount; ++i) {
            int ready = -1;
            if (::openni::OpenNI::waitForAnyStream(streams, 1, &ready, kFrameTimeout_ms) !=
                ::openni::STATUS_OK)
                throw CaptureError("meadow's OpenNI2 driver stopped at frame " + std::to_string(i) +
                                   " of " + std::to_string(info.frameCount) + " of " + uri + " (" +
                                   lastError() + "): check that frame's PNG in depth/");
            ::openni::VideoFrameRef frame;
            if (stream.readFrame(&frame) != ::openni::STATUS_OK)
                throw CaptureError("reading frame " + std::to_string(i) + " of " + uri +
                                   " through OpenNI2 failed (" + lastError() + ")");
            const cv::Mat1w depth_mm(
                frame.getHeight(), frame.getWidth(),
                static_cast<std::uint16_t*>(const_cast<void*>(frame.getData())),
                static_cast<std::size_t>(frame.getStrideInBytes()));
            double largest_mm = 0;
            cv::minMaxLoc(depth_mm, nullptr, &largest_mm);
            if (largest_mm > kLargestStorableDepth_mm)
                throw CaptureError("frame " + std::to_string(i) + " of " + uri +
                                   " holds depth 65535 mm, which an .oni file cannot store: "
                                   "set such pixels to 0 (no reading) first");
            if (progress) progress(i + 1, info.frameCount);
        }
        recorder.stop();
        stream.stop();
        // Destroying the recorder writes the frame index and end record: the file is complete.
        recorder.destroy();
    }
    return framesInOniFile(oniPath);
}

}  // namespace

int recordingToOni(const fs::path& recordingFolder, const fs::path& oniPath,
                   const FrameProgress& progress) {
    const RecordingInfo info = readRecordingInfo(recordingFolder);  // checks it, names problems
    auto runtime = Runtime::acquire();
    if (!meadowDriverInstalled())
        throw CaptureError("cannot serve " + recordingFolder.string() +
                           " to OpenNI2: meadow's driver " + kMeadowDriverFileName + " is not in " +
                           driverFolder().string() + "; " + howToLoadMeadowDriver());

    std::error_code ec;
    const fs::path folder = fs::absolute(recordingFolder, ec).lexically_normal();
    std::string uri = folder.string();
    if (uri.size() > 1 && uri.back() == '/') uri.pop_back();
    createParentFolder(oniPath);
    int written = -1;
    for (const auto startup : kRecorderStartups) {
        TemporaryOni tmp(oniPath);
        checkWritable(tmp.path(), oniPath);
        written = recordOnce(uri, tmp.path(), info, startup, progress);
        if (written == info.frameCount) {
            tmp.commitTo(oniPath);
            return written;
        }
    }
    throw CaptureError("OpenNI2's recorder kept " + std::to_string(written) + " of " +
                       std::to_string(info.frameCount) + " frames of " + uri + " in " +
                       std::to_string(std::size(kRecorderStartups)) +
                       " tries; nothing was written to " + oniPath.string() +
                       ": try again on a less busy machine");
}

int oniToRecording(const fs::path& oniPath, const fs::path& folder, const FrameProgress& progress) {
    if (const std::string why = whyNotReplaceableRecording(folder); !why.empty())
        throw CaptureError("refusing to overwrite " + folder.string() + ": " + why +
                           "; choose an empty or new folder");
    auto source = openOpenNiSource(oniPath.string());
    // Written beside the old recording and swapped in whole once complete.
    StagedFolder staged(folder);
    int written = 0;
    {
        RecordingWriter writer(staged.path(), source->info());
        while (auto frame = source->next()) {
            writer.write(frame->depth_mm);
            if (progress) progress(++written, source->info().frameCount);
        }
        if (writer.framesWritten() == 0)
            throw CaptureError(oniPath.string() + " holds no depth frame: nothing to convert");
        writer.finish();
        written = writer.framesWritten();
    }
    try {
        staged.commit();
    } catch (const Error& e) {
        throw CaptureError(e.what());
    }
    return written;
}

}  // namespace meadow::capture::ni
