#include "meadow/core/library_messages.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace meadow {

CapturedStderr::CapturedStderr() {
    std::fflush(stderr);
    char name[] = "/tmp/meadow_stderr_XXXXXX";
    file_ = ::mkstemp(name);
    if (file_ < 0) return;  // nothing caught: the library speaks as before
    ::unlink(name);
    saved_ = ::dup(STDERR_FILENO);
    if (saved_ < 0 || ::dup2(file_, STDERR_FILENO) < 0) {
        if (saved_ >= 0) ::close(saved_);
        ::close(file_);
        saved_ = file_ = -1;
    }
}

CapturedStderr::~CapturedStderr() {
    restore();
    if (file_ >= 0) ::close(file_);
}

void CapturedStderr::restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    saved_ = -1;
}

std::string CapturedStderr::text() {
    restore();
    if (file_ < 0) return {};
    std::string all;
    char chunk[512];
    ::lseek(file_, 0, SEEK_SET);
    for (ssize_t n; (n = ::read(file_, chunk, sizeof chunk)) > 0;)
        all.append(chunk, static_cast<std::size_t>(n));
    return oneLine(all);
}

std::string oneLine(std::string_view text) {
    std::string out;
    bool pendingBreak = false;
    for (const char c : text) {
        if (c == '\n' || c == '\r') {
            pendingBreak = !out.empty();
            continue;
        }
        if (pendingBreak) {
            while (!out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
            out += "; ";
            pendingBreak = false;
            if (c == ' ' || c == '\t') continue;
        }
        if ((c == ' ' || c == '\t') && !out.empty() && out.size() >= 2 &&
            out.compare(out.size() - 2, 2, "; ") == 0)
            continue;
        out += c;
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
    return out;
}

}  // namespace meadow
