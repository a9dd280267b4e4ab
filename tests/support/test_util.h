#pragma once
// Helpers every test program shares: scratch folders and running a command as a user would.
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace meadow::test {

// Scratch folders of this process, removed when it exits normally (a crash leaves them for a
// look). Named by process, so every run would otherwise leave its own set behind: a test
// machine gathered thousands.
class ScratchFolders {
public:
    static ScratchFolders& instance() {
        static ScratchFolders folders;
        return folders;
    }
    void add(const std::filesystem::path& dir) { dirs_.push_back(dir); }
    ScratchFolders(const ScratchFolders&) = delete;
    ScratchFolders& operator=(const ScratchFolders&) = delete;
    ~ScratchFolders() {
        std::error_code ignored;  // a folder a test removed itself is fine
        for (const auto& dir : dirs_) std::filesystem::remove_all(dir, ignored);
    }

private:
    ScratchFolders() = default;
    std::vector<std::filesystem::path> dirs_;
};

// A fresh, empty folder outside the repository, private to this process:
// <tmp>/meadow_<name>_<pid>, removed when the process exits (ScratchFolders).
inline std::filesystem::path freshTempDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("meadow_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    ScratchFolders::instance().add(dir);
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
