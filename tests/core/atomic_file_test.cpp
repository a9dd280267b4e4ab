#include "meadow/core/atomic_file.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "meadow/core/error.h"
#include "support/test_util.h"

namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
fs::path freshDir(const std::string& name) { return meadow::test::freshTempDir("atomic_" + name); }
}  // namespace

TEST(AtomicFile, CommitReplacesTheFileWhole) {
    const fs::path dir = freshDir("commit");
    const fs::path target = dir / "lib.json";
    meadow::writeFileAtomically(target, "old");
    meadow::writeFileAtomically(target, "new contents");
    EXPECT_EQ(slurp(target), "new contents");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1)
        << "no temporary file may be left behind";
}

TEST(AtomicFile, AbandonedWriteKeepsThePreviousFileAndLeavesNoTemporary) {
    const fs::path dir = freshDir("abandon");
    const fs::path target = dir / "lib.json";
    meadow::writeFileAtomically(target, "previous");
    {
        meadow::AtomicFile file(target);
        file.stream() << "half a libr";
        // no commit(): as if the writer threw half-way
    }
    EXPECT_EQ(slurp(target), "previous");
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(AtomicFile, UnwritableFolderIsAClearError) {
    EXPECT_THROW(meadow::writeFileAtomically("/proc/meadow_cannot_write_here/x.json", "x"),
                 meadow::Error);
}

TEST(AtomicFile, RecognisesAFileAndTheTemporaryItsWriterLeftButNothingElse) {
    EXPECT_TRUE(meadow::isFileOrItsTemporary("recording.json", "recording.json"));
    EXPECT_TRUE(meadow::isFileOrItsTemporary("recording.json.tmp.4242", "recording.json"));
    EXPECT_FALSE(meadow::isFileOrItsTemporary("recording.json.tmp.", "recording.json"));
    EXPECT_FALSE(meadow::isFileOrItsTemporary("recording.json.tmp.42x", "recording.json"));
    EXPECT_FALSE(meadow::isFileOrItsTemporary("recording.json.bak", "recording.json"));
    EXPECT_FALSE(meadow::isFileOrItsTemporary("notes.txt", "recording.json"));
}
