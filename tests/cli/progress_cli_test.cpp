// Progress on long work: a redrawn line on a terminal, nothing in a log. The terminal is a real
// pseudo-terminal from util-linux's script(1) (bsdutils, part of every Debian system).
#include <gtest/gtest.h>

#include "cli/cli_test_util.h"

using meadow::test::freshTempDir;
using meadow::test::runCommand;
using meadow::test::runMeadow;

namespace {

// Enough frames that the 100 ms redraw interval draws more than the final line.
const std::string kSynthArgs = "synth --preset quadratic-leaf --frames 12 --out ";

TEST(ProgressCli, SynthShowsProgressOnATerminalAndNothingWhenPiped) {
    if (runCommand("command -v script >/dev/null").exitCode != 0)
        GTEST_SKIP() << "script(1) (package bsdutils) is not installed";
    const std::string tty = (freshTempDir("progress_tty") / "rec").string();
    const auto onTerminal = runCommand("script -qec '" + std::string(MEADOW_EXE) + " " +
                                       kSynthArgs + tty + "' /dev/null");
    ASSERT_EQ(onTerminal.exitCode, 0) << onTerminal.output;
    EXPECT_NE(onTerminal.output.find("12/12"), std::string::npos) << onTerminal.output;
    EXPECT_NE(onTerminal.output.find('\r'), std::string::npos) << "the line is redrawn in place";

    const std::string piped = (freshTempDir("progress_pipe") / "rec").string();
    const auto inLog = runMeadow(kSynthArgs + piped + " 2>&1 | cat");
    ASSERT_EQ(inLog.exitCode, 0) << inLog.output;
    EXPECT_EQ(inLog.output.find("/12"), std::string::npos) << inLog.output;
    EXPECT_EQ(inLog.output.find('\r'), std::string::npos) << inLog.output;
}

}  // namespace
