#include "meadow/core/temporaries.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <map>
#include <mutex>
#include <system_error>
#include <thread>

namespace meadow {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kTemporaryInfix = ".tmp.";

struct Registry {
    std::mutex mutex;
    std::map<fs::path, fs::path> paths;  // temporary -> where it goes back to ("" for nowhere)
};

Registry& registry() {
    static Registry r;  // never destroyed before the signal thread is done with it
    return r;
}

sigset_t cleanupSignals() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    return set;
}

// Called once, on the way out. The lock is never released: a thread still writing blocks in
// registerTemporary instead of creating a temporary nobody would remove. Each temporary is
// first renamed, so a thread writing into a staged folder by its old name cannot put a file
// back into it while it is being removed. A thread already past registering may still make the
// folder again (creating a file's parent folders): the temporaries are removed again until two
// passes in a row find none of them, for at most kCleanupPasses passes.
void removeRegistered() {
    constexpr int kCleanupPasses = 20;
    constexpr auto kBetweenPasses = std::chrono::milliseconds(20);
    Registry& r = registry();
    r.mutex.lock();
    int quiet = 0;
    for (int pass = 0; pass < kCleanupPasses && quiet < 2; ++pass) {
        bool found = false;
        for (const auto& [path, restoreTo] : r.paths) {
            std::error_code ignored;
            if (!fs::exists(fs::symlink_status(path, ignored))) continue;
            found = true;
            if (!restoreTo.empty() && !fs::exists(fs::symlink_status(restoreTo, ignored))) {
                fs::rename(path, restoreTo, ignored);
                continue;
            }
            fs::path going = path;
            going += ".gone";
            fs::rename(path, going, ignored);
            fs::remove_all(ignored ? path : going, ignored);
        }
        quiet = found ? 0 : quiet + 1;
        if (quiet < 2) std::this_thread::sleep_for(kBetweenPasses);
    }
}

// Waits for the blocked signals; on one, removes the temporaries and ends the process by it.
void waitForSignals() {
    const sigset_t set = cleanupSignals();
    int signal = 0;
    while (sigwait(&set, &signal) != 0) {
    }
    removeRegistered();
    // The default action of the signal now ends the process, as it would have without us.
    struct sigaction action {};
    action.sa_handler = SIG_DFL;
    sigemptyset(&action.sa_mask);
    sigaction(signal, &action, nullptr);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, signal);
    pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
    raise(signal);
    _exit(128 + signal);  // not reached
}

// The pid of "<target>.tmp.<pid>[extra]", or 0 when `entry` is no temporary of `target`.
pid_t temporaryPid(std::string_view entry, std::string_view target) {
    if (entry.substr(0, target.size()) != target) return 0;
    std::string_view rest = entry.substr(target.size());
    if (rest.substr(0, kTemporaryInfix.size()) != kTemporaryInfix) return 0;
    rest.remove_prefix(kTemporaryInfix.size());
    pid_t pid = 0;
    std::size_t digits = 0;
    while (digits < rest.size() && rest[digits] >= '0' && rest[digits] <= '9' && digits < 9)
        pid = pid * 10 + (rest[digits++] - '0');
    return digits > 0 ? pid : 0;
}

}  // namespace

std::string temporarySuffix() { return std::string(kTemporaryInfix) + std::to_string(::getpid()); }

fs::path temporaryFor(const fs::path& target, const std::string& extra) {
    fs::path tmp = target;
    tmp += temporarySuffix() + extra;
    return tmp;
}

void registerTemporary(const fs::path& path, const fs::path& restoreTo) {
    Registry& r = registry();
    const std::lock_guard<std::mutex> lock(r.mutex);
    r.paths[path] = restoreTo;
}

void unregisterTemporary(const fs::path& path) {
    Registry& r = registry();
    const std::lock_guard<std::mutex> lock(r.mutex);
    r.paths.erase(path);
}

void installTemporaryCleanup() {
    static std::once_flag once;
    std::call_once(once, [] {
        const sigset_t set = cleanupSignals();
        pthread_sigmask(SIG_BLOCK, &set, nullptr);
        std::thread(waitForSignals).detach();
    });
}

int sweepStaleTemporaries(const fs::path& target) {
    const fs::path folder = target.has_parent_path() ? target.parent_path() : fs::path(".");
    const std::string name = target.filename().string();
    if (name.empty()) return 0;
    int removed = 0;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const pid_t pid = temporaryPid(it->path().filename().string(), name);
        if (pid <= 0 || pid == ::getpid()) continue;
        if (::kill(pid, 0) == 0 || errno != ESRCH) continue;  // alive, or not ours to know
        std::error_code ignored;
        // A folder moved aside by a swap that died before the new one took its place is the
        // only copy left: put it back.
        const bool aside = it->path().filename().string().ends_with(".old");
        if (aside && !fs::exists(fs::symlink_status(target, ignored))) {
            fs::rename(it->path(), target, ignored);
            continue;
        }
        removed += fs::remove_all(it->path(), ignored) > 0;
    }
    return removed;
}

bool isFileOrItsTemporary(std::string_view name, std::string_view fileName) {
    if (name.substr(0, fileName.size()) != fileName) return false;
    const std::string_view rest = name.substr(fileName.size());
    if (rest.empty()) return true;
    if (rest.substr(0, kTemporaryInfix.size()) != kTemporaryInfix ||
        rest.size() == kTemporaryInfix.size())
        return false;
    return rest.substr(kTemporaryInfix.size()).find_first_not_of("0123456789") ==
           std::string_view::npos;
}

}  // namespace meadow
