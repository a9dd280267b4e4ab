#pragma once
// Output that appears whole or not at all: data goes to "<path>.tmp.<pid>" and is renamed over
// <path> on commit(); the destructor removes the temporary if commit() never ran. A crash or
// early return therefore never leaves a half-written file, and an existing file survives.
#include <filesystem>
#include <fstream>
#include <string_view>

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

// True for "<fileName>" itself and for the temporary "<fileName>.tmp.<pid>" that an AtomicFile
// leaves behind when its process dies between writing and renaming.
bool isFileOrItsTemporary(std::string_view name, std::string_view fileName);

// Convenience: the whole file at once, atomically.
void writeFileAtomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace meadow
