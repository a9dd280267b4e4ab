#pragma once
// Output that appears whole or not at all: data goes to "<path>.tmp.<pid>" and is renamed over
// <path> on commit(); the destructor removes the temporary if commit() never ran. A crash or
// early return therefore never leaves a half-written file, and an existing file survives. The
// temporary is removed on SIGINT / SIGTERM, and a stale one of a killed run by the next
// AtomicFile for the same path (temporaries.h). Several AtomicFiles committed one after the
// other, once all are written, replace several outputs together.
#include <filesystem>
#include <fstream>
#include <string_view>

#include "meadow/core/temporaries.h"

namespace meadow {

class AtomicFile {
public:
    explicit AtomicFile(std::filesystem::path path);
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;
    ~AtomicFile();

    std::ofstream& stream() { return out_; }
    // Flushes, closes and renames; throws meadow::Error naming the path on failure.
    void commit();

private:
    std::filesystem::path path_;
    std::filesystem::path tmp_;
    std::ofstream out_;
    bool committed_ = false;
};

// Throws meadow::Error naming `path` when an AtomicFile could not be written there: for a long
// job to find out before it starts, not after. Leaves nothing behind.
void checkWritable(const std::filesystem::path& path);

// Convenience: the whole file at once, atomically.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace meadow
