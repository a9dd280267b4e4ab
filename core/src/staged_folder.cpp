#include "meadow/core/staged_folder.h"

#include <system_error>

#include "meadow/core/error.h"
#include "meadow/core/temporaries.h"

namespace meadow {

namespace fs = std::filesystem;

StagedFolder::StagedFolder(fs::path target)
    : target_(std::move(target)), staging_(temporaryFor(target_)) {
    std::error_code ec;
    if (target_.has_parent_path()) {
        fs::create_directories(target_.parent_path(), ec);
        if (ec)
            throw Error("cannot create folder " + target_.parent_path().string() + " for " +
                        target_.filename().string() + ": " + ec.message() +
                        "; check the path and permissions");
    }
    sweepStaleTemporaries(target_);
    fs::remove_all(staging_, ec);  // a leftover of this very pid (a reused pid)
    registerTemporary(staging_);
    fs::create_directory(staging_, ec);
    if (ec) {
        unregisterTemporary(staging_);
        throw Error("cannot create " + staging_.string() + ": " + ec.message() +
                    "; check that the folder is writable");
    }
}

StagedFolder::~StagedFolder() {
    if (committed_) return;
    std::error_code ignored;
    fs::remove_all(staging_, ignored);
    unregisterTemporary(staging_);
}

void StagedFolder::commit() {
    std::error_code ec;
    const bool replacing = fs::exists(fs::symlink_status(target_, ec));
    const fs::path aside = temporaryFor(target_, ".old");
    if (replacing) {
        registerTemporary(aside, target_);
        fs::rename(target_, aside, ec);
        if (ec) {
            unregisterTemporary(aside);
            throw Error("cannot move the old " + target_.string() + " aside: " + ec.message() +
                        "; check permissions on it and its folder");
        }
    }
    fs::rename(staging_, target_, ec);
    if (ec) {
        std::error_code ignored;
        if (replacing) fs::rename(aside, target_, ignored);  // put the old one back
        unregisterTemporary(aside);
        throw Error("cannot rename " + staging_.string() + " to " + target_.string() + ": " +
                    ec.message());
    }
    unregisterTemporary(staging_);
    committed_ = true;
    if (replacing) {
        std::error_code ignored;
        fs::remove_all(aside, ignored);
        unregisterTemporary(aside);
    }
}

}  // namespace meadow
