#pragma once
// Each verb of the `meadow` command lives in its own file and registers itself here.
// A verb is added only when it works end to end.
#include <CLI/CLI.hpp>

namespace meadow::cli {

// meadow convert RECORDING OUT.oni | IN.oni OUT_DIR (convert_command.cpp)
void addCaptureCommand(CLI::App& app);
void addConvertCommand(CLI::App& app);
// meadow synth --preset NAME --out DIR | --list (synth_command.cpp)
void addSynthCommand(CLI::App& app);
// meadow render SCENE --out DIR [--frames N] [--size WxH] (render_command.cpp)
void addRenderCommand(CLI::App& app);
// meadow view SCENE [--library LIB] [--size WxH] (view_command.cpp)
void addViewCommand(CLI::App& app);

}  // namespace meadow::cli
