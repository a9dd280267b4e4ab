#pragma once
// Runtime failures (missing file, corrupt data, driver errors) are thrown as one exception
// type per layer, all derived from meadow::Error. The message says what failed, which file,
// and what to do; only cli/ prints it and picks the exit code. Broken preconditions
// (programmer errors) are std::invalid_argument / std::logic_error instead.
#include <stdexcept>
#include <string>

namespace meadow {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace meadow
