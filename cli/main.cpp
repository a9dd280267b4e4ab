// The `meadow` command: parses arguments, calls the libraries, prints one clear line on error.
#include <CLI/CLI.hpp>
#include <iostream>

#include "commands.h"
#include "meadow/capture/error.h"

int main(int argc, char** argv) {
    CLI::App app{"meadow: capture real grass with a depth camera and render meadows of it"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "meadow 0.1.0");
    meadow::cli::addCaptureCommand(app);
    meadow::cli::addConvertCommand(app);
    meadow::cli::addSynthCommand(app);
    meadow::cli::addRenderCommand(app);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const meadow::Error& e) {
        std::cerr << "meadow: " << e.what() << '\n';
        return 2;
    } catch (const std::exception& e) {
        std::cerr << "meadow: internal error: " << e.what() << '\n';
        return 3;
    }
    return 0;
}
