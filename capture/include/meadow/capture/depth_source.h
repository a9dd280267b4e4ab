#pragma once
#include <memory>
#include <optional>
#include <string>

#include "meadow/capture/depth_frame.h"
#include "meadow/capture/recording_info.h"

namespace meadow::capture {

// A stream of depth frames: a recording folder, a plain PNG folder, an OpenNI2 device or
// .oni file. Frames come in order; next() returns nullopt at the end.
class DepthSource {
public:
    virtual ~DepthSource() = default;
    [[nodiscard]] virtual const RecordingInfo& info() const = 0;
    // Throws CaptureError on a corrupt or inconsistent frame (naming the file).
    virtual std::optional<DepthFrame> next() = 0;
};

// How to read a source that does not describe itself (a plain PNG folder).
struct SourceOptions {
    std::optional<Intrinsics> intrinsics;  // --intrinsics fx,fy,cx,cy
    std::optional<DepthUnit> depthUnit;    // --depth-unit mm|0.2mm|m
};

// Opens a recording folder (with recording.json), a plain folder of 16-bit PNGs (needs
// options.intrinsics and options.depthUnit), an .oni file, or "openni://" / "openni://URI"
// for a live device. Throws CaptureError with what to do when it cannot.
std::unique_ptr<DepthSource> openDepthSource(const std::string& uri,
                                             const SourceOptions& options = {});

}  // namespace meadow::capture
