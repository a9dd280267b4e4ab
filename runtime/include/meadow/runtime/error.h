#pragma once
#include "meadow/core/error.h"

namespace meadow::runtime {

// Runtime failures of the renderer (no EGL display or OpenGL 4.5, shader compile errors, bad
// scene files, GL errors caught by debug output). The message says what failed, which file,
// and what to do.
class RuntimeError : public Error {
public:
    using Error::Error;
};

}  // namespace meadow::runtime
