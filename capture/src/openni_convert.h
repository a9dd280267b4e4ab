#pragma once
// The conversions are declared in the public header: `meadow convert` is their user.
#include "meadow/capture/openni.h"
