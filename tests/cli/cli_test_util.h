#pragma once
// Runs the real `meadow` binary as a user would and captures what a user sees.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace meadow::test {

struct CommandResult {
    int exitCode = -1;
    std::string output;  // stdout and stderr together, as on a terminal
};

inline CommandResult runCommand(const std::string& command) {
    CommandResult result;
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> chunk{};
    while (std::fgets(chunk.data(), static_cast<int>(chunk.size()), pipe))
        result.output += chunk.data();
    const int status = ::pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

// `meadow ARGS` with the binary this build made.
inline CommandResult runMeadow(const std::string& args) {
    return runCommand(std::string(MEADOW_EXE) + " " + args);
}

inline std::filesystem::path freshTempDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("meadow_cli_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline int countLines(const std::string& text) {
    int n = 0;
    for (char c : text) n += c == '\n';
    return n;
}

}  // namespace meadow::test
