#include "video_writer.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "meadow/core/temporaries.h"
#include "meadow/runtime/error.h"

extern char** environ;

namespace meadow::cli {
namespace {

const char* const kInstallHint = "install it (Debian: apt-get install ffmpeg)";

// ffmpeg's last non-empty line of output: the reason it stopped.
std::string lastLine(const std::filesystem::path& log) {
    std::ifstream in(log);
    std::string line, last;
    while (std::getline(in, line))
        if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    return last.empty() ? "no message" : last;
}

}  // namespace

bool ffmpegAvailable() {
    const char* path = std::getenv("PATH");
    if (path == nullptr) return false;
    std::stringstream dirs(path);
    std::string dir;
    while (std::getline(dirs, dir, ':'))
        if (!dir.empty() && ::access((std::filesystem::path(dir) / "ffmpeg").c_str(), X_OK) == 0)
            return true;
    return false;
}

VideoWriter::VideoWriter(std::filesystem::path target, int width_px, int height_px, double fps)
    : target_(std::move(target)), width_(width_px), height_(height_px) {
    if (!ffmpegAvailable())
        throw runtime::RuntimeError("render: --video needs ffmpeg, which is not on the PATH; " +
                                    std::string(kInstallHint));
    sweepStaleTemporaries(target_);
    temporary_ = temporaryFor(target_, target_.extension().string());
    log_ = temporaryFor(target_, ".log");
    registerTemporary(temporary_);
    registerTemporary(log_);
    // A pipe whose reader has died must fail a write, not end meadow.
    std::signal(SIGPIPE, SIG_IGN);

    int fds[2];
    if (::pipe(fds) != 0) throw runtime::RuntimeError("render: cannot open a pipe to ffmpeg");
    const std::string size = std::to_string(width_) + "x" + std::to_string(height_);
    const std::string rate = std::to_string(fps);
    // yuv420p halves the chroma resolution, so both sides must be even: pad by a pixel if not.
    std::vector<std::string> args = {"ffmpeg",
                                     "-nostdin",
                                     "-hide_banner",
                                     "-loglevel",
                                     "error",
                                     "-y",
                                     "-f",
                                     "rawvideo",
                                     "-pix_fmt",
                                     "bgr24",
                                     "-s",
                                     size,
                                     "-r",
                                     rate,
                                     "-i",
                                     "pipe:0",
                                     "-vf",
                                     "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                     "-c:v",
                                     "libx264",
                                     "-pix_fmt",
                                     "yuv420p",
                                     "-movflags",
                                     "+faststart",
                                     temporary_.string()};
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
    posix_spawn_file_actions_addclose(&actions, fds[1]);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int spawned = posix_spawnp(&ffmpeg_, "ffmpeg", &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    if (spawned != 0) {
        ::close(fds[1]);
        ffmpeg_ = -1;
        throw runtime::RuntimeError("render: cannot start ffmpeg; " + std::string(kInstallHint));
    }
    pipe_ = ::fdopen(fds[1], "wb");
}

VideoWriter::~VideoWriter() {
    if (pipe_ != nullptr || ffmpeg_ > 0) stop();
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
    std::filesystem::remove(log_, ignored);
    unregisterTemporary(temporary_);
    unregisterTemporary(log_);
}

void VideoWriter::write(const cv::Mat& bgr) {
    if (bgr.type() != CV_8UC3 || bgr.cols != width_ || bgr.rows != height_)
        throw runtime::RuntimeError("render: a frame of the wrong size reached the video writer");
    const std::size_t rowBytes = static_cast<std::size_t>(width_) * 3;
    for (int y = 0; y < bgr.rows; ++y)
        if (std::fwrite(bgr.ptr(y), 1, rowBytes, pipe_) != rowBytes) {
            stop();
            throw runtime::RuntimeError("render: ffmpeg stopped while writing " + target_.string() +
                                        ": " + lastLine(log_));
        }
}

void VideoWriter::stop() {
    if (pipe_ != nullptr) std::fclose(pipe_);
    pipe_ = nullptr;
    if (ffmpeg_ > 0) {
        while (::waitpid(ffmpeg_, &status_, 0) < 0 && errno == EINTR) {
        }
        ffmpeg_ = -1;
    }
}

void VideoWriter::finish() {
    stop();
    if (!WIFEXITED(status_) || WEXITSTATUS(status_) != 0)
        throw runtime::RuntimeError("render: ffmpeg could not write " + target_.string() + ": " +
                                    lastLine(log_));
    std::filesystem::rename(temporary_, target_);
}

}  // namespace meadow::cli
