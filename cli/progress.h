#pragma once
// Progress for work longer than a couple of seconds: a single updating line on a terminal,
// nothing at all when stderr is not a TTY (logs, CI, pipes).
#include <chrono>
#include <cstddef>
#include <string>

namespace meadow::cli {

class Progress {
public:
    Progress(std::string label, std::size_t total);
    ~Progress();
    void update(std::size_t done);
    void finish();

private:
    std::string label_;
    std::size_t total_;
    bool enabled_;
    bool finished_ = false;
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point lastDraw_;
};

}  // namespace meadow::cli
