#include "meadow/core/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <system_error>

#include "meadow/core/error.h"
#include "meadow/core/temporaries.h"

namespace meadow {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(fs::path path) : path_(std::move(path)), tmp_(temporaryFor(path_)) {
    // Registered before anything is created: once an interrupted run's cleanup has begun,
    // registering waits for the end, so no folder is made that the cleanup has already passed.
    registerTemporary(tmp_);
    std::error_code ec;
    if (path_.has_parent_path()) {
        fs::create_directories(path_.parent_path(), ec);
        if (ec) {
            unregisterTemporary(tmp_);
            throw Error("cannot create folder " + path_.parent_path().string() + " for " +
                        path_.filename().string() + ": " + ec.message());
        }
    }
    if (fs::is_directory(path_, ec)) {
        unregisterTemporary(tmp_);
        throw Error("cannot write " + path_.string() + ": it is a folder; choose a file name");
    }
    sweepStaleTemporaries(path_);
    out_.open(tmp_, std::ios::binary | std::ios::trunc);
    if (!out_) {
        const int error = errno;
        unregisterTemporary(tmp_);
        throw Error("cannot write " + path_.string() + " (" + std::strerror(error) +
                    "): check the folder exists and is writable");
    }
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        out_.close();
        std::error_code ignored;
        fs::remove(tmp_, ignored);
        unregisterTemporary(tmp_);
    }
}

void AtomicFile::commit() {
    out_.flush();
    const bool ok = static_cast<bool>(out_);
    out_.close();
    if (!ok) throw Error("writing " + path_.string() + " failed (disk full?)");
    std::error_code ec;
    fs::rename(tmp_, path_, ec);
    if (ec)
        throw Error("cannot rename " + tmp_.string() + " to " + path_.string() + ": " +
                    ec.message());
    unregisterTemporary(tmp_);
    committed_ = true;
}

void checkWritable(const fs::path& path) {
    const AtomicFile probe(path);  // creates and, uncommitted, removes its temporary
}

void writeFileAtomically(const fs::path& path, std::string_view bytes) {
    AtomicFile file(path);
    file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    file.commit();
}

}  // namespace meadow
