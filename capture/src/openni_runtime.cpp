#include "openni_runtime.h"

#include <OpenNI.h>
#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <system_error>

#include "meadow/capture/error.h"

namespace meadow::capture::ni {

namespace fs = std::filesystem;

namespace {

std::mutex& runtimeMutex() {
    static std::mutex m;
    return m;
}

bool initialised = false;  // guarded by runtimeMutex()

std::weak_ptr<Runtime>& currentRuntime() {
    static std::weak_ptr<Runtime> current;
    return current;
}

bool isFolder(const fs::path& p) {
    std::error_code ec;
    return fs::is_directory(p, ec);
}

}  // namespace

std::shared_ptr<Runtime> Runtime::acquire() {
    std::lock_guard lock(runtimeMutex());
    if (auto existing = currentRuntime().lock()) return existing;
    if (initialised) return std::shared_ptr<Runtime>(new Runtime());

    const fs::path drivers = driverFolder();
    if (!isFolder(drivers))
        throw CaptureError("OpenNI2 driver folder " + drivers.string() +
                           " is missing: OpenNI2 looks for its drivers beside " +
                           loadedLibraryFolder().string() +
                           "/libOpenNI2.so.0; reinstall libopenni2-0, or point LD_LIBRARY_PATH at "
                           "a folder holding libOpenNI2.so.0 and OpenNI2/Drivers/");
    if (::openni::OpenNI::initialize() != ::openni::STATUS_OK)
        throw CaptureError("OpenNI2 failed to start (" + lastError() + ") with drivers from " +
                           drivers.string() +
                           ": check that folder holds OpenNI2 drivers (lib*.so.0, e.g. "
                           "libOniFile.so.0 for .oni files)");
    initialised = true;
    std::shared_ptr<Runtime> runtime(new Runtime());
    currentRuntime() = runtime;
    return runtime;
}

// OpenNI2 stays initialised until the process ends. Shutting it down and starting it again in
// one process races with the threads of Debian's file driver: the real-file round-trip test
// crashed now and then that way.
Runtime::~Runtime() = default;

std::string lastError() {
    std::string text = ::openni::OpenNI::getExtendedError();
    // OpenNI2 prefixes a tab per nesting level and ends with a newline; keep one line.
    for (char& c : text)
        if (c == '\n' || c == '\t' || c == '\r') c = ' ';
    const auto first = text.find_first_not_of(' ');
    if (first == std::string::npos) return "no details from OpenNI2";
    const auto last = text.find_last_not_of(' ');
    return text.substr(first, last - first + 1);
}

fs::path loadedLibraryFolder() {
    Dl_info info{};
    // Any function of libOpenNI2 names the file the dynamic loader picked.
    if (::dladdr(reinterpret_cast<void*>(&oniInitialize), &info) == 0 || info.dli_fname == nullptr)
        return {};
    return fs::path(info.dli_fname).parent_path();
}

fs::path driverFolder() { return loadedLibraryFolder() / "OpenNI2" / "Drivers"; }

bool meadowDriverInstalled() {
    std::error_code ec;
    return fs::is_regular_file(driverFolder() / kMeadowDriverFileName, ec);
}

fs::path privateFolder() {
    if (const char* fromEnvironment = std::getenv(kPrivateFolderVariable);
        fromEnvironment != nullptr && *fromEnvironment != '\0')
        return fs::path(fromEnvironment);
#ifdef MEADOW_OPENNI2_PRIVATE_DIR
    if (isFolder(MEADOW_OPENNI2_PRIVATE_DIR)) return fs::path(MEADOW_OPENNI2_PRIVATE_DIR);
#endif
    return {};
}

std::string howToLoadMeadowDriver() {
    const fs::path folder = privateFolder();
    if (folder.empty())
        return std::string("build the target meadow_openni2_folder (or set ") +
               kPrivateFolderVariable +
               " to a folder holding lib/libOpenNI2.so.0 and lib/OpenNI2/Drivers/" +
               kMeadowDriverFileName + ") and run with LD_LIBRARY_PATH=<that folder>/lib";
    return "run with LD_LIBRARY_PATH=" + (folder / "lib").string() +
           " (the `meadow` command does this by itself)";
}

}  // namespace meadow::capture::ni
