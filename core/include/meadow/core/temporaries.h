#pragma once
// Every output meadow writes goes first to a temporary beside it, "<target>.tmp.<pid>" (a file,
// or a whole folder), and is renamed into place only when complete (atomic_file.h,
// staged_folder.h). This file keeps those temporaries from outliving their run:
// - a process registers each temporary while it writes it; SIGINT, SIGTERM and SIGHUP remove
//   the registered ones before the process ends (installTemporaryCleanup);
// - a temporary a killed process left behind (SIGKILL, a crash, a power cut) is removed by the
//   next run that writes the same target (sweepStaleTemporaries), once its process is gone.
#include <filesystem>
#include <string>
#include <string_view>

namespace meadow {

// ".tmp.<pid of this process>".
[[nodiscard]] std::string temporarySuffix();

// The temporary this process writes `target` to: "<target>.tmp.<pid>" (+ extra, e.g. ".oni").
[[nodiscard]] std::filesystem::path temporaryFor(const std::filesystem::path& target,
                                                 const std::string& extra = "");

// While registered, `path` (a file or a folder) is removed if the process is interrupted; with
// `restoreTo`, it is the old output moved aside by a swap, and is renamed back there instead
// when nothing has taken that place yet.
void registerTemporary(const std::filesystem::path& path,
                       const std::filesystem::path& restoreTo = {});
void unregisterTemporary(const std::filesystem::path& path);

// Call first thing in main, before any thread starts: blocks SIGINT, SIGTERM and SIGHUP in
// every thread and waits for them on a thread of its own, which removes the registered
// temporaries and then ends the process by the same signal.
void installTemporaryCleanup();

// Removes "<target>.tmp.<pid>..." beside `target` whose process no longer runs. Returns how many.
int sweepStaleTemporaries(const std::filesystem::path& target);

// True for "<fileName>" itself and for its temporary "<fileName>.tmp.<pid>", which a process
// that died between writing and renaming leaves behind.
[[nodiscard]] bool isFileOrItsTemporary(std::string_view name, std::string_view fileName);

}  // namespace meadow
