#pragma once
// Runs the real `meadow` binary as a user would and captures what a user sees.
#include <filesystem>
#include <string>

#include "support/test_util.h"

namespace meadow::test {

// `meadow ARGS` with the binary this build made.
inline CommandResult runMeadow(const std::string& args) {
    return runCommand(std::string(MEADOW_EXE) + " " + args);
}

inline int countLines(const std::string& text) {
    int n = 0;
    for (char c : text) n += c == '\n';
    return n;
}

}  // namespace meadow::test
