#pragma once
// Helpers every test program shares: scratch folders and running a command as a user would.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace meadow::test {

// A fresh, empty folder outside the repository, private to this process:
// <tmp>/meadow_<name>_<pid>.
inline std::filesystem::path freshTempDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("meadow_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

struct CommandResult {
    int exitCode = -1;
    std::string output;  // stdout and stderr together, as on a terminal
};

// Runs `command` through the shell; -1 as exit code when it could not run or was killed.
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

}  // namespace meadow::test
