#include "meadow/core/atomic_file.h"

#include <unistd.h>

#include <system_error>

#include "meadow/core/error.h"

namespace meadow {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(fs::path path) : path_(std::move(path)) {
    tmp_ = path_;
    tmp_ += ".tmp." + std::to_string(::getpid());
    if (path_.has_parent_path()) {
        std::error_code ec;
        fs::create_directories(path_.parent_path(), ec);
        if (ec)
            throw Error("cannot create folder " + path_.parent_path().string() + ": " +
                        ec.message());
    }
    out_.open(tmp_, std::ios::binary | std::ios::trunc);
    if (!out_)
        throw Error("cannot write " + tmp_.string() + ": check the folder exists and is writable");
}

AtomicFile::~AtomicFile() {
    if (!committed_) {
        out_.close();
        std::error_code ignored;
        fs::remove(tmp_, ignored);
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
    committed_ = true;
}

bool isFileOrItsTemporary(std::string_view name, std::string_view fileName) {
    if (name.substr(0, fileName.size()) != fileName) return false;
    const std::string_view rest = name.substr(fileName.size());
    constexpr std::string_view kTmp = ".tmp.";  // AtomicFile's suffix, then the pid
    if (rest.empty()) return true;
    if (rest.substr(0, kTmp.size()) != kTmp || rest.size() == kTmp.size()) return false;
    return rest.substr(kTmp.size()).find_first_not_of("0123456789") == std::string_view::npos;
}

void writeFileAtomically(const fs::path& path, std::string_view bytes) {
    AtomicFile file(path);
    file.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    file.commit();
}

}  // namespace meadow
