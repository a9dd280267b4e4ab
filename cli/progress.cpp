#include "progress.h"

#include <unistd.h>

#include <cstdio>

namespace meadow::cli {

namespace {
// Redraw at most this often so a fast loop does not spend its time printing.
constexpr auto kRedrawInterval = std::chrono::milliseconds(100);
}  // namespace

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)),
      total_(total),
      enabled_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_ - kRedrawInterval) {}

Progress::~Progress() { finish(); }

void Progress::update(std::size_t done) {
    if (!enabled_ || finished_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - lastDraw_ < kRedrawInterval && done < total_) return;
    lastDraw_ = now;
    const double seconds = std::chrono::duration<double>(now - start_).count();
    std::fprintf(stderr, "\r%s: %zu/%zu (%.1f s)\x1b[K", label_.c_str(), done, total_, seconds);
    std::fflush(stderr);
}

void Progress::finish() {
    if (!enabled_ || finished_) return;
    finished_ = true;
    std::fputs("\r\x1b[K", stderr);
    std::fflush(stderr);
}

}  // namespace meadow::cli
