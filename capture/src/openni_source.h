#pragma once
// OpenNI2 depth sources (private to capture/): an .oni recording played back through OpenNI2's
// own file driver, or a live device ("openni://" for the first one found, "openni://URI" for a
// given one, e.g. a meadow recording folder served by meadow's OpenNI2 driver).
#include <memory>
#include <string>

#include "meadow/capture/depth_source.h"

namespace meadow::capture {

// uri: a path ending in ".oni", "openni://" or "openni://URI". Frames come in file order, depth
// in millimetres, intrinsics from the stream's fields of view, timestamps in seconds; next()
// returns nullopt at the end of a file. Throws CaptureError (with OpenNI's own message and what
// to do) when OpenNI2, the device or its depth stream cannot be opened.
std::unique_ptr<DepthSource> openOpenNiSource(const std::string& uri);

}  // namespace meadow::capture
