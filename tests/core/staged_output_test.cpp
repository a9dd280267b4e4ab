// Outputs appear whole or not at all: staged folders swap in whole, temporaries of a process
// that is gone are swept by the next run, and a folder moved aside by a swap that died is put
// back.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "meadow/core/atomic_file.h"
#include "meadow/core/error.h"
#include "meadow/core/staged_folder.h"
#include "meadow/core/temporaries.h"
#include "support/test_util.h"

namespace meadow {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

// A pid no process has: a child that has exited and been reaped.
pid_t deadPid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return child;
}

TEST(StagedFolder, CommitSwapsTheWholeFolderAndAnAbandonedOneLeavesTheOldOne) {
    const fs::path dir = test::freshTempDir("staged_folder");
    const fs::path out = dir / "out";
    fs::create_directories(out);
    std::ofstream(out / "old.txt") << "old";
    {
        StagedFolder staged(out);
        std::ofstream(staged.path() / "new.txt") << "new";
        EXPECT_TRUE(fs::exists(out / "old.txt")) << "nothing changes before commit";
    }  // abandoned
    EXPECT_EQ(readAll(out / "old.txt"), "old");
    EXPECT_FALSE(fs::exists(out / "new.txt"));
    {
        StagedFolder staged(out);
        std::ofstream(staged.path() / "new.txt") << "new";
        staged.commit();
    }
    EXPECT_FALSE(fs::exists(out / "old.txt")) << "the old folder is replaced whole";
    EXPECT_EQ(readAll(out / "new.txt"), "new");
    for (const auto& e : fs::directory_iterator(dir))
        EXPECT_EQ(e.path().filename(), "out") << "left behind: " << e.path();
}

TEST(Temporaries, StaleOnesOfAGoneProcessAreSweptAndLiveOnesKept) {
    const fs::path dir = test::freshTempDir("temporaries_sweep");
    const fs::path target = dir / "lib.json";
    const pid_t gone = deadPid();
    const fs::path stale = fs::path(target).concat(".tmp." + std::to_string(gone));
    const fs::path live = fs::path(target).concat(".tmp." + std::to_string(::getppid()));
    const fs::path other = dir / "lib.json.bak";
    for (const fs::path& p : {stale, live, other}) std::ofstream(p) << "x";
    EXPECT_EQ(sweepStaleTemporaries(target), 1);
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_TRUE(fs::exists(live)) << "its process still runs";
    EXPECT_TRUE(fs::exists(other)) << "not a temporary";
}

TEST(Temporaries, AFolderMovedAsideByADeadSwapIsPutBack) {
    const fs::path dir = test::freshTempDir("temporaries_aside");
    const fs::path target = dir / "rec";
    const pid_t gone = deadPid();
    const fs::path aside = fs::path(target).concat(".tmp." + std::to_string(gone) + ".old");
    const fs::path staged = fs::path(target).concat(".tmp." + std::to_string(gone));
    fs::create_directories(aside);
    std::ofstream(aside / "recording.json") << "old";
    fs::create_directories(staged);
    sweepStaleTemporaries(target);
    EXPECT_EQ(readAll(target / "recording.json"), "old") << "the only copy left is restored";
    EXPECT_FALSE(fs::exists(staged));
    EXPECT_FALSE(fs::exists(aside));
}

TEST(Temporaries, AnAtomicFileSweepsWhatAKilledRunLeftBeforeWriting) {
    const fs::path dir = test::freshTempDir("temporaries_atomic");
    const fs::path target = dir / "stats.csv";
    const fs::path stale = fs::path(target).concat(".tmp." + std::to_string(deadPid()));
    std::ofstream(stale) << std::string(1000, 'x');
    writeFileAtomically(target, "frame\n");
    EXPECT_FALSE(fs::exists(stale));
    EXPECT_EQ(readAll(target), "frame\n");
}

TEST(Temporaries, ATemporaryIsTheTargetWithThisProcessesPid) {
    EXPECT_EQ(temporaryFor("a/b.oni", ".oni").string(),
              "a/b.oni.tmp." + std::to_string(::getpid()) + ".oni");
}

TEST(CheckWritable, NamesTheTargetAndLeavesNothing) {
    const fs::path dir = test::freshTempDir("check_writable");
    EXPECT_NO_THROW(checkWritable(dir / "lib.json"));
    EXPECT_TRUE(fs::is_empty(dir));
    try {
        checkWritable("/proc/meadow/lib.json");
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("lib.json"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace meadow
