#pragma once
// `meadow render --video FILE.mp4`: frames piped as raw BGR to ffmpeg, which encodes H.264 in
// MP4 (yuv420p, so every player opens it). ffmpeg writes a temporary beside the target
// (core/temporaries.h), renamed into place only when it has finished cleanly.
#include <sys/types.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/core/mat.hpp>
#include <string>

namespace meadow::cli {

// Whether an `ffmpeg` program is on the PATH.
[[nodiscard]] bool ffmpegAvailable();

class VideoWriter {
public:
    // Starts ffmpeg for width x height frames at fps. Throws runtime::RuntimeError when ffmpeg is
    // missing or does not start.
    VideoWriter(std::filesystem::path target, int width_px, int height_px, double fps);
    ~VideoWriter();  // a video not finished is removed, the target left as it was
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    // One CV_8UC3 frame of the size given. Throws runtime::RuntimeError when ffmpeg has stopped.
    void write(const cv::Mat& bgr);
    // Ends the stream, waits for ffmpeg and renames the video into place. Throws
    // runtime::RuntimeError with ffmpeg's last message when it failed.
    void finish();

private:
    void stop();  // closes the pipe and waits for ffmpeg; its exit status
    std::filesystem::path target_, temporary_, log_;
    int width_, height_;
    FILE* pipe_ = nullptr;
    pid_t ffmpeg_ = -1;
    int status_ = 0;
};

}  // namespace meadow::cli
