#pragma once
// A folder of outputs that appears whole or not at all (a recording, a render's frames): it is
// written under "<target>.tmp.<pid>" and swapped in for <target> on commit(). An existing
// <target> is moved aside first and removed only once the new one is in place, so a run killed
// at any point leaves the old folder or the new one, never a mix. Whether <target> may be
// replaced at all is the caller's to decide, before staging. The temporary is removed when the
// run fails, is interrupted (SIGINT / SIGTERM), or, once its process is gone, by the next run.
#include <filesystem>

namespace meadow {

class StagedFolder {
public:
    // Creates the temporary folder (and target's parents). Throws meadow::Error naming the path.
    explicit StagedFolder(std::filesystem::path target);
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;
    ~StagedFolder();

    // Where to write.
    [[nodiscard]] const std::filesystem::path& path() const { return staging_; }
    [[nodiscard]] const std::filesystem::path& target() const { return target_; }
    // Swaps the staged folder in; throws meadow::Error naming the paths when the disk refuses.
    void commit();

private:
    std::filesystem::path target_;
    std::filesystem::path staging_;
    bool committed_ = false;
};

}  // namespace meadow
