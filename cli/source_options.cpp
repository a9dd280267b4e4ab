#include "source_options.h"

#include "meadow/capture/recording.h"

namespace meadow::cli {

void addSourceOptions(CLI::App& command, SourceArgs& args) {
    command.add_option("--intrinsics", args.intrinsics,
                       "fx,fy,cx,cy in pixels, for a plain PNG folder without recording.json "
                       "(e.g. TUM RGB-D: 525,525,319.5,239.5)");
    command
        .add_option("--depth-unit", args.depthUnit,
                    "Unit of the PNG values of a plain folder: mm, 0.2mm (TUM RGB-D) or m")
        ->check(CLI::IsMember({"mm", "0.2mm", "m"}));
}

capture::SourceOptions toSourceOptions(const SourceArgs& args) {
    capture::SourceOptions options;
    if (!args.intrinsics.empty()) options.intrinsics = capture::parseIntrinsics(args.intrinsics);
    if (!args.depthUnit.empty()) options.depthUnit = capture::parseDepthUnit(args.depthUnit);
    return options;
}

}  // namespace meadow::cli
