#include "meadow/modeling/archetype_library.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "meadow/modeling/error.h"

namespace fs = std::filesystem;
using namespace meadow::modeling;

namespace {

ArchetypeLibrary sampleLibrary() {
    ArchetypeLibrary lib;
    lib.generator = "test";
    lib.source = "synthetic";
    Archetype a;
    a.name = "leaf-1";
    a.spine_m = {{0, 0, 0}, {0.01f, 0.08f, 0.002f}, {0.05f, 0.15f, -0.001f}};
    a.width.width_m = {0.010f, 0.014f, 0.012f, 0.006f, 0.0005f};
    a.nearestShape = AnalyticShape::TriangleTip;
    a.tau = 0.7f;
    a.fit.spineRms_mm = 0.4f;
    a.fit.asymmetric = true;
    a.fit.skeletonPoints = 57;
    a.fit.baseExtension_mm = 21.5f;
    a.fit.baseNotRooted = false;
    a.fit.tipExtension_mm = 7.25f;
    a.source = {"samples/recordings/quadratic-leaf",
                2,
                3,
                {"too-thin: mean width 1.9 px"},
                {{2, 3}, {5, 1}},
                {{7, 2}}};
    a.knots_m = {{0, 0, 0}, {0.02f, 0.1f, 0}, {0.05f, 0.15f, -0.001f}};
    Archetype b = a;
    b.name = "grass-2";
    b.width.width_m = {0.003f, 0.0f};
    b.nearestShape = AnalyticShape::Triangle;
    lib.archetypes = {a, b};
    lib.merges = {{"leaf-1", {"leaf-7", "leaf-9"}, 0.0021f}};
    return lib;
}

// A valid document with one field replaced, to test each bad input in isolation.
std::string withArchetypeField(const std::string& field, const std::string& rawValue) {
    nlohmann::json doc = nlohmann::json::parse(serialiseArchetypeLibrary(sampleLibrary()));
    doc["archetypes"][0][field] = nlohmann::json::parse(rawValue);
    return doc.dump();
}

void expectRejected(const std::string& text, const std::string& expectedInMessage) {
    try {
        parseArchetypeLibrary(text, "lib.json");
        ADD_FAILURE() << "accepted: " << text.substr(0, 200);
    } catch (const ModelingError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("lib.json"), std::string::npos) << msg;
        EXPECT_NE(msg.find(expectedInMessage), std::string::npos) << "message: " << msg;
    }
}

}  // namespace

TEST(ArchetypeLibrary, WriteThenReadIsIdentity) {
    const ArchetypeLibrary lib = sampleLibrary();
    const ArchetypeLibrary back = parseArchetypeLibrary(serialiseArchetypeLibrary(lib), "mem");
    ASSERT_EQ(back.archetypes.size(), lib.archetypes.size());
    for (std::size_t i = 0; i < lib.archetypes.size(); ++i) {
        const Archetype &a = lib.archetypes[i], &b = back.archetypes[i];
        EXPECT_EQ(a.name, b.name);
        EXPECT_EQ(a.spine_m.v0, b.spine_m.v0);
        EXPECT_EQ(a.spine_m.v1, b.spine_m.v1);
        EXPECT_EQ(a.spine_m.v2, b.spine_m.v2);
        EXPECT_EQ(a.width.width_m, b.width.width_m);
        EXPECT_EQ(a.nearestShape, b.nearestShape);
        EXPECT_EQ(a.tau, b.tau);
        EXPECT_EQ(a.fit.spineRms_mm, b.fit.spineRms_mm);
        EXPECT_EQ(a.fit.asymmetric, b.fit.asymmetric);
        EXPECT_EQ(a.fit.skeletonPoints, b.fit.skeletonPoints);
        EXPECT_EQ(a.fit.baseExtension_mm, b.fit.baseExtension_mm);
        EXPECT_EQ(a.fit.baseNotRooted, b.fit.baseNotRooted);
        EXPECT_EQ(a.fit.tipExtension_mm, b.fit.tipExtension_mm);
        EXPECT_EQ(a.source.recording, b.source.recording);
        EXPECT_EQ(a.source.frame, b.source.frame);
        EXPECT_EQ(a.source.bladeId, b.source.bladeId);
        EXPECT_EQ(a.source.flags, b.source.flags);
        ASSERT_EQ(a.source.seenIn.size(), b.source.seenIn.size());
        for (std::size_t k = 0; k < a.source.seenIn.size(); ++k) {
            EXPECT_EQ(a.source.seenIn[k].frame, b.source.seenIn[k].frame);
            EXPECT_EQ(a.source.seenIn[k].bladeId, b.source.seenIn[k].bladeId);
        }
        ASSERT_EQ(b.source.alsoSeenIn.size(), 1u);
        EXPECT_EQ(b.source.alsoSeenIn[0].frame, 7);
        EXPECT_EQ(b.source.alsoSeenIn[0].bladeId, 2);
        EXPECT_EQ(a.knots_m, b.knots_m);
    }
    ASSERT_EQ(back.merges.size(), 1u);
    EXPECT_EQ(back.merges[0].merged, lib.merges[0].merged);
    EXPECT_EQ(back.source, "synthetic");
}

TEST(ArchetypeLibrary, SavedFileLoadsBackAndAFailedSaveKeepsIt) {
    const fs::path dir = fs::temp_directory_path() / "meadow_archetype_library_test";
    fs::remove_all(dir);
    const fs::path path = dir / "lib.json";
    saveArchetypeLibrary(sampleLibrary(), path);
    EXPECT_EQ(loadArchetypeLibrary(path).archetypes.size(), 2u);
    EXPECT_THROW(saveArchetypeLibrary(ArchetypeLibrary{}, path), ModelingError);
    EXPECT_EQ(loadArchetypeLibrary(path).archetypes.size(), 2u) << "the old library must survive";
}

TEST(ArchetypeLibrary, MissingFileIsAClearError) {
    EXPECT_THROW(loadArchetypeLibrary("/nonexistent/lib.json"), ModelingError);
}

TEST(ArchetypeLibrary, RejectsMalformedDocumentsWithTheReason) {
    expectRejected("{\"format\": ", "not valid JSON");
    expectRejected("[1, 2]", "JSON object");
    expectRejected(R"({"format": "something-else", "version": 1})",
                   "expected \"meadow.archetype-library\"");
    expectRejected(R"({"format": "meadow.archetype-library", "version": 99, "archetypes": []})",
                   "version 99 is not supported");
    expectRejected(R"({"format": "meadow.archetype-library", "version": 1, "archetypes": []})",
                   "no archetypes");
}

TEST(ArchetypeLibrary, RejectsNaNInfinityAndOutOfRangeValuesNamingTheField) {
    std::string nanText = serialiseArchetypeLibrary(sampleLibrary());
    nanText.replace(nanText.find("\"tau\": ") + 7, 3, "NaN");
    expectRejected(nanText, "NaN");
    std::string overflowText = serialiseArchetypeLibrary(sampleLibrary());
    overflowText.replace(overflowText.find("\"tau\": ") + 7, 3, "1e999");
    expectRejected(overflowText, "number overflow");
    expectRejected(withArchetypeField("tau", "1.5"), "archetypes[0].tau: must lie in [0, 1]");
    expectRejected(withArchetypeField("width_m", "[0.01, -0.002]"),
                   "archetypes[0].width_m[1]: is negative");
    expectRejected(withArchetypeField("width_m", "[0.01]"), "at least 2 samples");
    nlohmann::json doc = nlohmann::json::parse(serialiseArchetypeLibrary(sampleLibrary()));
    doc["archetypes"][0]["fit"]["tip_extension_mm"] = -3;
    expectRejected(doc.dump(), "archetypes[0].fit.tip_extension_mm: must not be negative");
    doc["archetypes"][0]["fit"]["tip_extension_mm"] = 3;
    doc["archetypes"][0]["fit"]["base_not_rooted"] = "no";
    expectRejected(doc.dump(), "archetypes[0].fit.base_not_rooted: must be true or false");
    expectRejected(withArchetypeField("nearest_shape", "\"hexagon\""), "unknown shape 'hexagon'");
    expectRejected(
        withArchetypeField("spine_m", R"({"v0": [0,0,0], "v1": [0,0.1], "v2": [0,0.2,0]})"),
        "archetypes[0].spine_m.v1: must be an array of 3 numbers");
    expectRejected(withArchetypeField("name", "7"), "archetypes[0].name: must be a string");
    doc = nlohmann::json::parse(serialiseArchetypeLibrary(sampleLibrary()));
    doc["archetypes"][0]["source"]["flags"] = nlohmann::json::array({1});
    expectRejected(doc.dump(), "archetypes[0].source.flags: must hold reason lines");
    doc["archetypes"][0]["source"]["flags"] = "too-thin";
    expectRejected(doc.dump(), "archetypes[0].source.flags");
    doc["archetypes"][0]["source"]["flags"] = nlohmann::json::array();
    doc["archetypes"][0]["source"]["seen_in"] = nlohmann::json::array({7});
    expectRejected(doc.dump(), "archetypes[0].source.seen_in[0]: must be an object");
    doc["archetypes"][0]["source"]["seen_in"] = R"([{"frame": 3, "blade_id": 1.5}])"_json;
    expectRejected(doc.dump(), "archetypes[0].source.seen_in[0].blade_id: must be an integer");
}

TEST(ArchetypeLibrary, ALibraryWrittenBeforeSourceFlagsAndSightingsStillReads) {
    nlohmann::json doc = nlohmann::json::parse(serialiseArchetypeLibrary(sampleLibrary()));
    for (nlohmann::json& a : doc["archetypes"]) {
        a["source"].erase("flags");
        a["source"].erase("seen_in");
    }
    const ArchetypeLibrary back = parseArchetypeLibrary(doc.dump(), "old");
    ASSERT_EQ(back.archetypes.size(), 2u);
    EXPECT_TRUE(back.archetypes[0].source.flags.empty());
    EXPECT_TRUE(back.archetypes[0].source.seenIn.empty());
    EXPECT_EQ(back.archetypes[0].source.frame, 2);
}

// The stem is optional: a library with one keeps its height and view count, one without has
// none, and a height out of range or views under 1 are refused naming the field.
TEST(ArchetypeLibrary, TheStemIsOptionalAndChecked) {
    ArchetypeLibrary lib = sampleLibrary();
    EXPECT_FALSE(parseArchetypeLibrary(serialiseArchetypeLibrary(lib), "mem").stem);
    lib.stem = StemMeasure{0.625f, 12};
    const ArchetypeLibrary back = parseArchetypeLibrary(serialiseArchetypeLibrary(lib), "mem");
    ASSERT_TRUE(back.stem);
    EXPECT_EQ(back.stem->height_m, 0.625f);
    EXPECT_EQ(back.stem->views, 12);
    nlohmann::json doc = nlohmann::json::parse(serialiseArchetypeLibrary(lib));
    doc["stem"]["height_m"] = 625;  // millimetres
    expectRejected(doc.dump(), "stem.height_m: must lie in [0, 10");
    doc["stem"]["height_m"] = 0.625;
    doc["stem"]["views"] = 0;
    expectRejected(doc.dump(), "stem.views");
}
