#pragma once
#include "meadow/core/error.h"

namespace meadow::capture {

// Runtime failures of the capture layer (unreadable recording, driver errors, bad frames).
class CaptureError : public Error {
public:
    using Error::Error;
};

}  // namespace meadow::capture
