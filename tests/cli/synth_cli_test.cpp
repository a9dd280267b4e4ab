// `meadow synth` as a user runs it: the committed samples regenerate identically, and bad input
// gets one clear line and a non-zero exit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "cli/cli_test_util.h"

namespace fs = std::filesystem;
using meadow::test::countLines;
using meadow::test::freshTempDir;
using meadow::test::runMeadow;

namespace {

const fs::path kSamples = fs::path(MEADOW_SOURCE_DIR) / "samples" / "recordings";

nlohmann::json readJson(const fs::path& file) {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
}

// Same structure and strings; numbers equal to 1e-7 (a tenth of a micrometre): the floats are
// written as their shortest decimal, so anything beyond that is a real change.
void expectSameJson(const nlohmann::json& a, const nlohmann::json& b, const std::string& path) {
    if (a.is_number() && b.is_number()) {
        EXPECT_NEAR(a.get<double>(), b.get<double>(), 1e-7) << path;
        return;
    }
    ASSERT_EQ(a.type(), b.type()) << path;
    if (a.is_object()) {
        ASSERT_EQ(a.size(), b.size()) << path;
        for (auto it = a.begin(); it != a.end(); ++it) {
            ASSERT_TRUE(b.contains(it.key())) << path << "." << it.key();
            expectSameJson(it.value(), b.at(it.key()), path + "." + it.key());
        }
    } else if (a.is_array()) {
        ASSERT_EQ(a.size(), b.size()) << path;
        for (std::size_t i = 0; i < a.size(); ++i)
            expectSameJson(a[i], b[i], path + "[" + std::to_string(i) + "]");
    } else {
        EXPECT_EQ(a, b) << path;
    }
}

void expectSamePixels(const fs::path& a, const fs::path& b) {
    const cv::Mat x = cv::imread(a.string(), cv::IMREAD_UNCHANGED);
    const cv::Mat y = cv::imread(b.string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(x.empty()) << a;
    ASSERT_FALSE(y.empty()) << b;
    ASSERT_EQ(x.type(), CV_16UC1) << a;
    ASSERT_EQ(x.type(), y.type()) << b;
    ASSERT_EQ(x.size(), y.size()) << b;
    EXPECT_EQ(cv::countNonZero(x != y), 0) << a << " and " << b << " differ";
}

}  // namespace

TEST(SynthCli, RegeneratingTheCommittedQuadraticLeafSampleGivesTheSameFiles) {
    // The exact command of samples/regenerate.sh.
    const fs::path committed = kSamples / "quadratic-leaf";
    const fs::path out = freshTempDir("synth_regen") / "quadratic-leaf";
    const auto r =
        runMeadow("synth --preset quadratic-leaf --frames 3 --seed 1 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const nlohmann::json truth = readJson(out / "truth" / "blades.json");
    expectSameJson(truth, readJson(committed / "truth" / "blades.json"), "blades.json");
    expectSameJson(readJson(out / "recording.json"), readJson(committed / "recording.json"),
                   "recording.json");
    ASSERT_EQ(truth.at("frames").size(), 3u);
    for (const char* frame : {"000000.png", "000001.png", "000002.png"}) {
        expectSamePixels(out / "depth" / frame, committed / "depth" / frame);
        expectSamePixels(out / "truth" / "labels" / frame, committed / "truth" / "labels" / frame);
    }
}

TEST(SynthCli, ListShowsEveryPresetOnALineOfItsOwn) {
    const auto r = runMeadow("synth --list");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_EQ(countLines(r.output), 12) << r.output;
    for (const char* name :
         {"slim-grass", "quadratic-leaf", "shrub-leaf", "bamboo-leaf", "sharp-tip", "touching",
          "asymmetric", "curl", "thin", "tilted", "noisy", "wind"})
        EXPECT_NE(r.output.find(std::string(name) + "  "), std::string::npos) << name;
}

TEST(SynthCli, UnknownPresetFailsWithOneLineNamingTheKnownPresets) {
    const fs::path out = freshTempDir("synth_unknown") / "rec";
    const auto r = runMeadow("synth --preset lawn --out " + out.string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(countLines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find("lawn"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("slim-grass"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("wind"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing written for a bad preset";
}

TEST(SynthCli, OutOfRangeOrMalformedNumbersAreRejectedNamingTheOption) {
    const std::string out = (freshTempDir("synth_bad") / "rec").string();
    for (const std::string bad : {"--frames 0", "--frames x", "--distance 3", "--distance -1",
                                  "--blades 13", "--noise -0.5", "--seed -4"}) {
        const auto r = runMeadow("synth --preset slim-grass --out " + out + " " + bad);
        EXPECT_EQ(r.exitCode, 2) << bad;
        const std::string option = bad.substr(0, bad.find(' '));
        EXPECT_NE(r.output.find(option), std::string::npos) << bad << ": " << r.output;
        EXPECT_EQ(countLines(r.output), 1) << bad << ": one line, got\n" << r.output;
    }
    const auto missing = runMeadow("synth --preset slim-grass");
    EXPECT_EQ(missing.exitCode, 2);
    EXPECT_NE(missing.output.find("--out"), std::string::npos) << missing.output;
}

TEST(MeadowCli, UsageErrorsAreOneLineExitingTwoAndHelpExitsZero) {
    for (const std::string bad : {"", "fly", "synth --bogus", "render", "capture --out x.json"}) {
        const auto r = runMeadow(bad);
        EXPECT_EQ(r.exitCode, 2) << "'" << bad << "': " << r.output;
        EXPECT_EQ(countLines(r.output), 1) << "'" << bad << "': one line, got\n" << r.output;
        EXPECT_EQ(r.output.rfind("meadow: ", 0), 0u) << r.output;
    }
    for (const std::string verb : {"", "synth", "capture", "convert", "render", "view"}) {
        const auto r = runMeadow(verb + " --help");
        EXPECT_EQ(r.exitCode, 0) << verb << ": " << r.output;
        EXPECT_NE(r.output.find("Options:"), std::string::npos) << verb << ": " << r.output;
    }
}

TEST(MeadowCli, EveryVerbsHelpIsShortWithOneLineAnOptionAndExamples) {
    constexpr int kMaxLines = 60;
    constexpr std::size_t kMaxCharacters = 4000;
    for (const std::string verb : {"synth", "capture", "convert", "render", "view"}) {
        const auto r = runMeadow(verb + " --help");
        ASSERT_EQ(r.exitCode, 0) << verb << ": " << r.output;
        EXPECT_LE(countLines(r.output), kMaxLines) << verb << ":\n" << r.output;
        EXPECT_LE(r.output.size(), kMaxCharacters) << verb << ":\n" << r.output;
        EXPECT_NE(r.output.find("Examples:\n  meadow " + verb), std::string::npos) << verb << ":\n"
                                                                                   << r.output;
        // No measured figures: the help points to the docs instead.
        EXPECT_EQ(r.output.find("README"), std::string::npos) << verb << ":\n" << r.output;
        EXPECT_EQ(r.output.find("Measured"), std::string::npos) << verb << ":\n" << r.output;
        EXPECT_NE(r.output.find("docs/"), std::string::npos) << verb << ":\n" << r.output;
    }
}

TEST(SynthCli, HelpExplainsEveryOptionAndItsDefault) {
    const auto r = runMeadow("synth --help");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    for (const char* text : {"--preset", "--out", "--frames", "=3", "--seed", "=1", "--noise",
                             "--distance", "--blades", "--list"})
        EXPECT_NE(r.output.find(text), std::string::npos) << text << " missing in\n" << r.output;
}
