#include "source_options.h"

#include "meadow/capture/recording.h"

namespace meadow::cli {

void addSourceOptions(CLI::App& command, SourceArgs& args, const std::string& group) {
    command
        .add_option("--intrinsics", args.intrinsics,
                    "fx,fy,cx,cy in pixels, for a PNG folder without recording.json")
        ->group(group);
    command
        .add_option("--depth-unit", args.depthUnit,
                    "Unit of a PNG folder's values: " + capture::kDepthUnitNames.list(", "))
        ->check(CLI::IsMember(capture::kDepthUnitNames.names()))
        ->group(group);
}

capture::SourceOptions toSourceOptions(const SourceArgs& args) {
    capture::SourceOptions options;
    if (!args.intrinsics.empty()) options.intrinsics = capture::parseIntrinsics(args.intrinsics);
    if (!args.depthUnit.empty()) options.depthUnit = capture::parseDepthUnit(args.depthUnit);
    return options;
}

}  // namespace meadow::cli
