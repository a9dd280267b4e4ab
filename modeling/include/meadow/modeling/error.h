#pragma once
#include "meadow/core/error.h"

namespace meadow::modeling {

// Runtime failures of the modeling layer (unreadable library, failed fit on bad input).
class ModelingError : public Error {
public:
    using Error::Error;
};

}  // namespace meadow::modeling
