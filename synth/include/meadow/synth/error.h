#pragma once
#include "meadow/core/error.h"

namespace meadow::synth {

// Runtime failures of the test-data layer (unknown preset, unreadable truth, disk refusals).
class SynthError : public Error {
public:
    using Error::Error;
};

}  // namespace meadow::synth
