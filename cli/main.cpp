// The `meadow` command: parses arguments, calls the libraries, prints one clear line on error.
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.h"
#include "meadow/capture/frame_memory.h"
#include "meadow/core/error.h"
#include "meadow/core/temporaries.h"

int main(int argc, char** argv) {
    // First, before any thread starts: an interrupted run removes the temporaries it was
    // writing (every output is written to one and renamed into place when complete).
    meadow::installTemporaryCleanup();
    meadow::capture::keepFrameBuffersResident();  // capture and render run frame after frame
    CLI::App app{"meadow: capture real grass with a depth camera and render meadows of it"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "meadow 0.1.0");
    // Wide enough for "--option TYPE:{choices}=default" and its text on one line: one line an
    // option. Set before the verbs are added, which copy it.
    app.get_formatter()->column_width(48);
    // One line per error, as for meadow's own errors (CLI11's default adds a second line).
    app.failure_message([](const CLI::App*, const CLI::Error& e) {
        return "meadow: " + std::string(e.what()) + "; see --help for the options\n";
    });
    meadow::cli::addCaptureCommand(app);
    meadow::cli::addConvertCommand(app);
    meadow::cli::addSynthCommand(app);
    meadow::cli::addRenderCommand(app);
    meadow::cli::addViewCommand(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // --help and --version exit 0; a usage error exits 2 like every other user error.
        return app.exit(e) == 0 ? 0 : 2;
    } catch (const meadow::Error& e) {
        std::cerr << "meadow: " << e.what() << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "meadow: internal error: " << e.what() << '\n';
        return 3;
    }
    return 0;
}
