// `meadow synth --plant` as a user runs it: a made plant of known organs rendered on the bench
// into a recording with its truth, and one-line errors for what cannot work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <string>

#include "cli_test_util.h"
#include "meadow/modeling/archetype_library.h"
#include "meadow/synth/library_score.h"
#include "meadow/synth/plant_synthesize.h"
#include "support/made_plant.h"
#include "support/shared_data.h"

namespace fs = std::filesystem;
using meadow::test::countLines;
using meadow::test::freshTempDir;
using meadow::test::runMeadow;

namespace {

// A shared maize shoot's scan ("v-9-1"), synthesised on a turntable of `views` views through
// `sensor` into `rec`: synth's exit code, or -1 where the shared data is not present.
int sharedShootOnATurntable(const std::string& shoot, const fs::path& rec,
                            const std::string& sensor = "kinect-v1", int views = 12) {
    const fs::path scan =
        meadow::test::sharedDataDir() / "real/maize-label3d" / (shoot + "-l-r.txt");
    if (!fs::exists(scan)) return -1;
    return runMeadow("synth --plant " + scan.string() + " --sensor " + sensor + " --turntable " +
                     std::to_string(views) + " --out " + rec.string())
        .exitCode;
}

// Every view of `rec` captured alone as a potted plant into `lib`, one archetype per blade.
meadow::test::CommandResult captureEachViewAlone(const fs::path& rec, const fs::path& lib) {
    return runMeadow("capture " + rec.string() +
                     " --subject potted-plant --fuse 1 --assume-still --per-group --out " +
                     lib.string());
}

TEST(PlantSynthCli, AMadePlantBecomesATurntableRecordingWithItsTruth) {
    const fs::path dir = freshTempDir("plant_synth");
    const fs::path plant = meadow::test::writeMadePlant(dir / "made.txt");
    const fs::path out = dir / "rec";
    const auto r =
        runMeadow("synth --plant " + plant.string() + " --turntable 4 --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("2 leaves and a stem"), std::string::npos) << r.output;
    const meadow::synth::PlantTruth truth = meadow::synth::readPlantTruth(out / "truth/plant.json");
    ASSERT_EQ(truth.views.size(), 4u);
    for (int v = 0; v < 4; ++v) {
        const meadow::synth::PlantTruthView& view = truth.views[static_cast<std::size_t>(v)];
        EXPECT_FLOAT_EQ(view.azimuth_deg, 90.f * static_cast<float>(v));
        const cv::Mat depth = cv::imread(
            (out / "depth" / (std::string("00000") + std::to_string(v) + ".png")).string(),
            cv::IMREAD_UNCHANGED);
        const cv::Mat labels =
            cv::imread((out / "truth" / view.labels).string(), cv::IMREAD_UNCHANGED);
        ASSERT_FALSE(depth.empty());
        ASSERT_EQ(labels.size(), depth.size());
        ASSERT_EQ(view.organs.size(), 3u);
        int stems = 0;
        for (const auto& o : view.organs) {
            stems += o.stem;
            EXPECT_EQ(o.visiblePixels, cv::countNonZero(labels == o.id)) << "organ " << o.id;
        }
        EXPECT_EQ(stems, 1);
        // Pot, floor and wall are in every view.
        for (int label :
             {meadow::synth::kFloorLabel, meadow::synth::kWallLabel, meadow::synth::kPotLabel})
            EXPECT_GT(cv::countNonZero(labels == label), 100) << "label " << label;
    }
}

// The made plant's leaves leave its stem at 5 and 10 cm: captured as a potted plant,
// the library's stem runs from its foot to the higher node, 10 cm, within the pot's rim and a
// few pixels (3 cm), and capture prints it. Each leaf starts where it leaves the stem: none is
// continued down the stem to the foot, so no archetype is longer than the longer leaf (with
// a 10 % margin; rooted at the foot, they reach well beyond it).
TEST(PlantSynthCli, AMadePlantsStemHeightIsInTheLibrary) {
    const fs::path dir = freshTempDir("plant_stem");
    const fs::path plant = meadow::test::writeMadePlant(dir / "made.txt");
    const fs::path rec = dir / "rec";
    ASSERT_EQ(runMeadow("synth --plant " + plant.string() + " --turntable 4 --out " + rec.string())
                  .exitCode,
              0);
    const std::string capture =
        "capture " + rec.string() + " --fuse 1 --per-group --assume-still --keep-flagged --out ";
    // --subject potted-plant is the clusters finder and the stem-graph partition.
    const auto c = runMeadow(capture + (dir / "lib.json").string() + " --subject potted-plant");
    ASSERT_EQ(c.exitCode, 0) << c.output;
    EXPECT_NE(c.output.find("stem 0."), std::string::npos) << c.output;
    // A partition given stands over the subject's: the contour partition reports no stem.
    const auto contour = runMeadow(capture + (dir / "contour.json").string() +
                                   " --subject potted-plant --partition contour");
    ASSERT_EQ(contour.exitCode, 0) << contour.output;
    EXPECT_EQ(contour.output.find("stem 0."), std::string::npos) << contour.output;
    const auto library = meadow::modeling::loadArchetypeLibrary(dir / "lib.json");
    ASSERT_TRUE(library.stem);
    EXPECT_NEAR(library.stem->height_m, meadow::test::kMadeLeaves[1].attach_m, 0.03f);
    EXPECT_GE(library.stem->views, 1);
    const float longest = meadow::test::kMadeLeaves[0].length_m();
    ASSERT_FALSE(library.archetypes.empty());
    for (const auto& archetype : library.archetypes)
        EXPECT_LE(archetype.height_m(), 1.1f * longest) << archetype.name;
}

// A turntable recording of a real maize shoot (12 views 30 deg apart) given to capture as one
// folder: the motion test finds that the plant changes every frame, and the frames are segmented
// one by one, never fused, into one library, whichever way the plant is found (fused, a turning
// plant's frames keep only its stem and pot, which change least: the test reads the first frame
// alone). The plant's own readings change as a turning plant's do, so its views are registered
// and joined as --turntable's are. (A small plant, as the made one, changes too little between
// views to be told from a still one: docs/capture.md#motion-test.)
TEST(PlantSynthCli, ATurntableRecordingIsCapturedFrameByFrame) {
    const fs::path dir = freshTempDir("plant_turntable");
    const fs::path rec = dir / "rec";
    const int synthesised = sharedShootOnATurntable("v-9-1", rec);
    if (synthesised < 0) GTEST_SKIP() << "shared data not present: maize-label3d v-9-1";
    ASSERT_EQ(synthesised, 0);
    // Told nothing, capture finds the plant turning and segments each frame alone, as views of
    // a turning plant; with --per-group the library is one archetype per blade and view.
    const fs::path perView = dir / "per_view.json", joined = dir / "joined.json",
                   toldNothing = dir / "told_nothing.json";
    for (const std::string args :
         {"--keep-flagged --subject tuft --per-group", "--subject potted-plant --per-group"}) {
        const auto c =
            runMeadow("capture " + rec.string() + " --out " + perView.string() + " " + args);
        EXPECT_NE(c.output.find("segmented one by one, without recurring readings, as views of "
                                "a turning plant"),
                  std::string::npos)
            << args << "\n"
            << c.output;
    }
    const auto plain = runMeadow("capture " + rec.string() + " --subject potted-plant --out " +
                                 toldNothing.string());
    ASSERT_EQ(plain.exitCode, 0) << plain.output;
    EXPECT_NE(plain.output.find("a turning plant: "), std::string::npos) << plain.output;
    // Told it is a turntable, capture registers the views and leaves out the archetypes of a leaf
    // another view shows longer, and those no other view shows: fewer than frame by frame, the
    // kept ones naming the views they stand for.
    const auto t =
        runMeadow("capture " + rec.string() +
                  " --subject potted-plant --turntable --verbose --out " + joined.string());
    ASSERT_EQ(t.exitCode, 0) << t.output;
    // Most views are registered (9 of 11 when measured), each to the one before it.
    const std::size_t at = t.output.find("a turning plant: ");
    ASSERT_NE(at, std::string::npos) << t.output;
    EXPECT_GE(std::stoi(t.output.substr(at + 17)), 8) << t.output;
    EXPECT_EQ(t.output.find("most views lay on no view"), std::string::npos) << t.output;
    EXPECT_NE(t.output.find("frame 3: turned "), std::string::npos) << t.output;
    const auto eachView = meadow::modeling::loadArchetypeLibrary(perView);
    const auto library = meadow::modeling::loadArchetypeLibrary(joined);
    EXPECT_LT(library.archetypes.size(), eachView.archetypes.size());
    std::size_t standsFor = 0;
    for (const auto& a : library.archetypes) standsFor += a.source.alsoSeenIn.size();
    const std::size_t seenOnceAt = t.output.find("seen-in-one-view-only (");
    ASSERT_NE(seenOnceAt, std::string::npos) << t.output;
    const std::size_t seenOnce = std::stoul(t.output.substr(seenOnceAt + 23));
    EXPECT_EQ(library.archetypes.size() + standsFor + seenOnce, eachView.archetypes.size());
    // Found turning, the views were joined as --turntable joins them.
    EXPECT_EQ(meadow::modeling::loadArchetypeLibrary(toldNothing).archetypes.size(),
              library.archetypes.size());
}

// A young maize shoot through the Kinect v2: its leaves are two or three pixels wide, lost to
// their mixed readings with the wall behind, and the plant is found in one view of twelve, so
// no view lies on one before it. The user is told what to change.
TEST(PlantSynthCli, ATurntableWhoseViewsMostlyDoNotRegisterSaysWhatToChange) {
    const fs::path dir = freshTempDir("plant_unregistered");
    const fs::path rec = dir / "rec";
    const int synthesised = sharedShootOnATurntable("v-6-2", rec, "kinect-v2");
    if (synthesised < 0) GTEST_SKIP() << "shared data not present: maize-label3d v-6-2";
    ASSERT_EQ(synthesised, 0);
    const auto c =
        runMeadow("capture " + rec.string() + " --subject potted-plant --turntable --out " +
                  (dir / "lib.json").string());
    ASSERT_EQ(c.exitCode, 0) << c.output;
    const std::size_t at = c.output.find("a turning plant: ");
    ASSERT_NE(at, std::string::npos) << c.output;
    const int registered = std::stoi(c.output.substr(at + 17));
    EXPECT_LT(2 * registered, 11) << c.output;  // 0 of 11 when measured
    EXPECT_NE(c.output.find("most views lay on no view before them"), std::string::npos)
        << c.output;
    EXPECT_NE(c.output.find("bring the camera closer"), std::string::npos) << c.output;
}

// Maize's lowest leaves leave the stem just above the pot and hang below its rim, beside it. Seen
// from the side (a shared shoot through the RealSense D435, the second of four views), two of
// them hang past the pot's sides: each comes out a leaf of its own, an archetype lying along it,
// not a piece of the pot left out with the rim. (Before, what lay wholly below the stem's lowest
// junction was left out as the pot's, and both were lost to the stem.)
TEST(PlantSynthCli, LowLeavesHangingBesideThePotAreLeaves) {
    const fs::path dir = freshTempDir("plant_low_leaves");
    const fs::path rec = dir / "rec", lib = dir / "lib.json";
    const int synthesised = sharedShootOnATurntable("v-9-1", rec, "realsense-d435", 4);
    if (synthesised < 0) GTEST_SKIP() << "shared data not present: maize-label3d v-9-1";
    ASSERT_EQ(synthesised, 0);
    const auto c = captureEachViewAlone(rec, lib);
    ASSERT_EQ(c.exitCode, 0) << c.output;
    const auto truth = meadow::synth::readScoringTruth(rec / "truth/plant.json");
    ASSERT_EQ(truth.views.size(), 4u);
    const cv::Mat1w& labels = truth.views[1].labels;
    // The label most (60 %) of an archetype's spine lies on (within 2 px), or 0.
    const auto lyingOn = [&](const meadow::modeling::Archetype& a) {
        std::map<int, int> votes;
        const std::vector<glm::vec3> spine = meadow::synth::spineInCamera(a);
        for (const glm::vec3& p_m : spine) {
            const glm::vec2 uv = truth.intrinsics.project(p_m);
            std::set<int> near;
            for (int dy = -2; dy <= 2; ++dy)
                for (int dx = -2; dx <= 2; ++dx) {
                    const cv::Point p(static_cast<int>(std::lround(uv.x)) + dx,
                                      static_cast<int>(std::lround(uv.y)) + dy);
                    if (cv::Rect({}, labels.size()).contains(p)) near.insert(labels(p));
                }
            for (const int label : near) ++votes[label];
        }
        for (const auto& [label, n] : votes)
            if (label > 0 && n >= 0.6 * static_cast<double>(spine.size())) return label;
        return 0;
    };
    std::set<int> alongLeaves;
    for (const auto& a : meadow::modeling::loadArchetypeLibrary(lib).archetypes)
        if (a.source.frame == truth.views[1].frame) alongLeaves.insert(lyingOn(a));
    for (const int hanging : {4, 5})  // the scan's organs 4 and 5
        EXPECT_TRUE(alongLeaves.count(hanging)) << "leaf " << hanging << " of view 1\n" << c.output;
}

// A maize seedling (the shared v-3-1, 0.2 m tall) 0.8 m from the RealSense D435: seen edge-on,
// its leaves in one plane, it covers fewer pixels than plant finding asks of a plant (1382 of
// 1645 in the view 60 deg round). It stands in a pot of its own, so it is the plant: every one
// of six views holds blades. (Before, that view said "no plant".)
TEST(PlantSynthCli, ASeedlingSeenEdgeOnInItsPotIsFound) {
    const fs::path dir = freshTempDir("plant_seedling");
    const fs::path rec = dir / "rec", lib = dir / "lib.json";
    const int synthesised = sharedShootOnATurntable("v-3-1", rec, "realsense-d435", 6);
    if (synthesised < 0) GTEST_SKIP() << "shared data not present: maize-label3d v-3-1";
    ASSERT_EQ(synthesised, 0);
    const auto c = captureEachViewAlone(rec, lib);
    ASSERT_EQ(c.exitCode, 0) << c.output;
    std::set<int> viewsWithBlades;
    for (const auto& a : meadow::modeling::loadArchetypeLibrary(lib).archetypes)
        viewsWithBlades.insert(a.source.frame);
    for (int view = 0; view < 6; ++view)
        EXPECT_TRUE(viewsWithBlades.count(view)) << "view " << view << "\n" << c.output;
}

TEST(PlantSynthCli, WhatCannotWorkIsOneLineAndExitCodeTwo) {
    const fs::path dir = freshTempDir("plant_synth_bad");
    const fs::path plant = meadow::test::writeMadePlant(dir / "made.txt");
    const std::string out = " --out " + (dir / "rec").string();
    struct Case {
        std::string args, mention;
    };
    for (const Case& c : {
             Case{"synth --plant " + (dir / "none.txt").string() + out, "none.txt"},
             Case{"synth --plant " + plant.string() + " --plant-unit m" + out, "--plant-unit"},
             Case{"synth --plant " + plant.string() + " --plant-unit inch" + out, "inch"},
             Case{"synth --plant " + plant.string() + " --frames 5" + out, "--turntable"},
             Case{"synth --plant " + plant.string() + " --preset thin" + out, "not both"},
             Case{"synth --plant " + plant.string() + " --sensor lidar" + out, "lidar"},
             Case{"synth --plant " + plant.string(), "--out"},
         }) {
        const auto r = runMeadow(c.args);
        EXPECT_EQ(r.exitCode, 2) << c.args << "\n" << r.output;
        EXPECT_EQ(countLines(r.output), 1) << c.args << "\n" << r.output;
        EXPECT_NE(r.output.find(c.mention), std::string::npos) << c.args << "\n" << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "rec")) << "nothing written";
}

}  // namespace
