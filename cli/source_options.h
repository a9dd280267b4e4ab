#pragma once
// The options that say how to read a depth source that does not describe itself (a plain
// folder of 16-bit PNGs): shared by every verb that takes a SOURCE.
#include <CLI/CLI.hpp>
#include <string>

#include "meadow/capture/depth_source.h"

namespace meadow::cli {

struct SourceArgs {
    std::string intrinsics;  // "fx,fy,cx,cy" in pixels
    std::string depthUnit;   // mm | 0.2mm | m
};

void addSourceOptions(CLI::App& command, SourceArgs& args, const std::string& group);
// Throws meadow::Error with what to pass when the text is malformed.
capture::SourceOptions toSourceOptions(const SourceArgs& args);

}  // namespace meadow::cli
