// `meadow convert`: a meadow recording folder <-> an OpenNI .oni file.
//
//   meadow convert RECORDING OUT.oni   serves the folder through meadow's OpenNI2 driver and
//                                      records it with openni::Recorder: a genuine .oni file
//   meadow convert IN.oni OUT_DIR      plays the file through OpenNI2 and writes a recording
//
// meadow's driver is loaded only when the process starts with LD_LIBRARY_PATH naming the
// private OpenNI2 folder (OpenNI2 finds drivers beside the libOpenNI2.so.0 the dynamic loader
// picked, and the loader reads LD_LIBRARY_PATH once, at start-up). Rather than make every user
// learn that, convert re-executes itself with the folder on LD_LIBRARY_PATH when it needs the
// driver and the driver is not there: one extra process start, invisible, and a command that
// simply works. Setting LD_LIBRARY_PATH by hand (or installing the driver next to the system's
// OpenNI2 drivers) skips the restart.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "meadow/capture/error.h"
#include "meadow/capture/openni.h"
#include "meadow/capture/recording.h"
#include "progress.h"
// capture's OpenNI2 conversions are private to capture/ (they would need a public header
// meadow/capture/openni.h); the CLI is their only user.

namespace meadow::cli {

namespace {

namespace fs = std::filesystem;
namespace ni = capture::ni;
using capture::CaptureError;

// Set in the restarted process, so that a driver that still does not load is reported instead
// of restarting forever.
constexpr const char* kRestartedVariable = "MEADOW_OPENNI_RESTARTED";
constexpr const char* kUsage =
    "give `meadow convert RECORDING OUT.oni` or `meadow convert IN.oni OUT_DIR`";

bool endsWithOni(const std::string& path) {
    if (path.size() < 4) return false;
    std::string tail = path.substr(path.size() - 4);
    std::transform(tail.begin(), tail.end(), tail.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return tail == ".oni";
}

std::vector<std::string> ownArguments() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    const std::string all{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    std::vector<std::string> args;
    for (std::size_t start = 0; start < all.size();) {
        const std::size_t end = all.find('\0', start);
        args.push_back(all.substr(start, end - start));
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return args;
}

// Starts this command again with meadow's private OpenNI2 folder first on LD_LIBRARY_PATH.
// Returns only by throwing.
[[noreturn]] void restartWithMeadowDriver() {
    if (std::getenv(kRestartedVariable) != nullptr)
        throw CaptureError(std::string("meadow's OpenNI2 driver is still not loaded after "
                                       "restarting with LD_LIBRARY_PATH=") +
                           (std::getenv("LD_LIBRARY_PATH") ? std::getenv("LD_LIBRARY_PATH") : "") +
                           " (OpenNI2 loaded " + ni::driverFolder().string() +
                           "): check that folder holds " + ni::kMeadowDriverFileName);
    const fs::path folder = ni::privateFolder();
    if (folder.empty())
        throw CaptureError("meadow's OpenNI2 driver folder was not found: " +
                           ni::howToLoadMeadowDriver());
    const fs::path lib = folder / "lib";
    std::error_code ec;
    if (!fs::is_regular_file(lib / "libOpenNI2.so.0", ec) ||
        !fs::is_regular_file(lib / "OpenNI2" / "Drivers" / ni::kMeadowDriverFileName, ec))
        throw CaptureError("meadow's OpenNI2 folder " + folder.string() +
                           " lacks lib/libOpenNI2.so.0 or lib/OpenNI2/Drivers/" +
                           ni::kMeadowDriverFileName +
                           ": rebuild the target meadow_openni2_folder, or set " +
                           ni::kPrivateFolderVariable + " to a complete folder");
    std::string path = lib.string();
    if (const char* old = std::getenv("LD_LIBRARY_PATH"); old != nullptr && *old != '\0')
        path += std::string(":") + old;
    ::setenv("LD_LIBRARY_PATH", path.c_str(), 1);
    ::setenv(kRestartedVariable, "1", 1);

    std::vector<std::string> args = ownArguments();
    std::vector<char*> argv;
    for (std::string& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);
    std::cout.flush();
    std::cerr.flush();
    ::execv("/proc/self/exe", argv.data());
    throw CaptureError(std::string("cannot restart meadow with its OpenNI2 driver (") +
                       std::strerror(errno) + "): " + ni::howToLoadMeadowDriver());
}

struct ConvertOptions {
    std::string input;
    std::string output;
};

void runConvert(const ConvertOptions& options) {
    const bool fromOni = endsWithOni(options.input);
    const bool toOni = endsWithOni(options.output);
    if (fromOni == toOni)
        throw CaptureError("convert needs exactly one .oni side (got " + options.input + " and " +
                           options.output + "): " + kUsage);
    std::optional<Progress> progress;
    const auto report = [&](int done, int total) {
        if (!progress)
            progress.emplace("convert " + options.input, static_cast<std::size_t>(total));
        progress->update(static_cast<std::size_t>(done));
    };
    int frames = 0;
    if (toOni) {
        // Check the recording before (perhaps) restarting, so a typo is reported at once.
        capture::readRecordingInfo(options.input);
        if (!ni::meadowDriverInstalled()) restartWithMeadowDriver();
        frames = ni::recordingToOni(options.input, options.output, report);
    } else {
        frames = ni::oniToRecording(options.input, options.output, report);
    }
    if (progress) progress->finish();
    std::cout << "meadow convert: " << frames << " frames written to " << options.output << '\n';
}

}  // namespace

void addConvertCommand(CLI::App& app) {
    auto options = std::make_shared<ConvertOptions>();
    CLI::App* convert = app.add_subcommand(
        "convert",
        "Convert a recording folder to an OpenNI .oni file (played through meadow's OpenNI2 "
        "driver and recorded by OpenNI2), or an .oni file to a recording folder");
    convert->add_option("INPUT", options->input, "a recording folder, or an .oni file")->required();
    convert
        ->add_option("OUTPUT", options->output,
                     "the .oni file to write, or the recording folder to write")
        ->required();
    convert->footer(R"(Examples:
  meadow convert samples/recordings/quadratic-leaf tuft.oni
  meadow convert tuft.oni rec/

Outputs appear whole or not at all. Depth is kept bit for bit; intrinsics travel as OpenNI2
fields of view (principal point at the image centre). Reference: docs/cli.md.)");
    convert->callback([options] { runConvert(*options); });
}

}  // namespace meadow::cli
