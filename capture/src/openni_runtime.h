#pragma once
// OpenNI2 plumbing (namespace ni, so that ::openni stays OpenNI2's own) shared by capture's OpenNI2
// sources and converters (private to capture/): one refcounted initialisation of the library, error
// text, and where its drivers live.
//
// OpenNI2 finds its drivers in <folder of the libOpenNI2.so.0 that was loaded>/OpenNI2/Drivers
// (lib*.so.0 files). meadow builds a private copy of that layout, with its own driver that
// serves a meadow recording folder as a live device; a process uses it when it starts with
// LD_LIBRARY_PATH=<private folder>/lib (the `meadow` command re-executes itself that way).
#include <filesystem>
#include <memory>
#include <string>

#include "meadow/capture/openni.h"

namespace meadow::capture::ni {

// Every user of OpenNI2 holds one. The first acquire() initialises OpenNI2, which then stays
// initialised until the process ends (see ~Runtime for why it is never shut down).
class Runtime {
public:
    // Initialises OpenNI2 unless done already. Throws CaptureError when the driver
    // folder is missing or OpenNI2 refuses to start.
    static std::shared_ptr<Runtime> acquire();
    ~Runtime();
    Runtime(const Runtime&) = delete;
    Runtime& operator=(const Runtime&) = delete;

private:
    Runtime() = default;
};

// OpenNI's own last error text, whitespace trimmed, or "no details from OpenNI2".
std::string lastError();

}  // namespace meadow::capture::ni
