#include "meadow/core/json_reader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "support/test_util.h"

namespace meadow {
namespace {

// The error a call throws, or "" when it throws none.
template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const JsonError& e) {
        return e.what();
    }
    return "";
}

TEST(JsonReader, MalformedTextIsASyntaxErrorNamingNaNAndOverflowToo) {
    for (const std::string text : {"{\"a\": ", "{\"a\": NaN}", "{\"a\": 1e999}", ""}) {
        try {
            (void)parseJsonObject(text);
            ADD_FAILURE() << "accepted: " << text;
        } catch (const JsonError& e) {
            EXPECT_EQ(e.kind(), JsonError::Kind::Syntax) << text;
            EXPECT_NE(std::string(e.what()).find("not valid JSON"), std::string::npos) << e.what();
        }
    }
    try {
        (void)parseJsonObject("[1, 2]");
        ADD_FAILURE() << "accepted an array";
    } catch (const JsonError& e) {
        EXPECT_EQ(e.kind(), JsonError::Kind::NotAnObject);
    }
}

TEST(JsonReader, FormatAndVersionAreCheckedApart) {
    const JsonFormat expected{"meadow.thing", 2};
    EXPECT_NO_THROW(
        checkJsonFormat(parseJsonObject(R"({"format": "meadow.thing", "version": 2})"), expected));
    const auto kindOf = [&](const std::string& text) {
        try {
            checkJsonFormat(parseJsonObject(text), expected);
        } catch (const JsonError& e) {
            return e.kind();
        }
        return JsonError::Kind::Syntax;  // none thrown: never expected below
    };
    EXPECT_EQ(kindOf(R"({"version": 2})"), JsonError::Kind::WrongFormat);
    EXPECT_EQ(kindOf(R"({"format": "meadow.other", "version": 2})"), JsonError::Kind::WrongFormat);
    EXPECT_EQ(kindOf(R"({"format": 7, "version": 2})"), JsonError::Kind::WrongFormat);
    EXPECT_EQ(kindOf(R"({"format": "meadow.thing", "version": 3})"), JsonError::Kind::WrongVersion);
    EXPECT_EQ(kindOf(R"({"format": "meadow.thing"})"), JsonError::Kind::Field);
    EXPECT_EQ(kindOf(R"({"format": "meadow.thing", "version": "2"})"), JsonError::Kind::Field);
    EXPECT_NE(errorOf([&] {
                  checkJsonFormat(parseJsonObject(R"({"format": "meadow.thing", "version": 3})"),
                                  expected);
              }).find("version 3 is not supported (this meadow reads version 2)"),
              std::string::npos);
}

TEST(JsonReader, EveryFieldErrorNamesItsPath) {
    const nlohmann::json doc = parseJsonObject(R"({
        "name": 3, "count": 2.5, "big": 3000000000, "ratio": 2, "huge": 1e300,
        "point": [1, 2], "list": [1, "x"], "inner": {"flag": "yes"}, "range": [3, 1]})");
    const JsonReader r(doc, "thing");
    EXPECT_EQ(errorOf([&] { (void)r.string("missing"); }), "thing.missing: is missing");
    EXPECT_EQ(errorOf([&] { (void)r.string("name"); }), "thing.name: must be a string, got 3");
    EXPECT_EQ(errorOf([&] { (void)r.integer("count"); }),
              "thing.count: must be an integer, got 2.5");
    EXPECT_EQ(errorOf([&] { (void)r.integer("big", 0, 100); }),
              "thing.big: must lie in [0, 100], got 3000000000");
    EXPECT_EQ(errorOf([&] { (void)r.floatNumber("ratio", 0.f, 0.f, 1.f); }),
              "thing.ratio: must lie in [0, 1], got 2");
    EXPECT_EQ(errorOf([&] { (void)r.floatNumber("huge"); }),
              "thing.huge: is too large, got 1e+300");
    EXPECT_EQ(errorOf([&] { (void)r.vec3("point"); }),
              "thing.point: must be an array of 3 numbers");
    EXPECT_EQ(errorOf([&] { (void)r.floatArray("list"); }),
              "thing.list[1]: must be a number, got \"x\"");
    EXPECT_EQ(errorOf([&] { (void)r.object("inner").boolean("flag"); }),
              "thing.inner.flag: must be true or false, got \"yes\"");
    EXPECT_NE(errorOf([&] {
                  (void)r.range("range", {0.f, 1.f}, 0.f, 10.f);
              }).find("thing.range"),
              std::string::npos);
    EXPECT_EQ(errorOf([&] { r.onlyKeys({"name", "count"}); }), "thing.big: unknown field");
}

TEST(JsonReader, OptionalFieldsFallBackOnlyWhenAbsent) {
    const nlohmann::json doc = parseJsonObject(R"({"a": 0.5, "b": true})");
    const JsonReader r(doc);
    EXPECT_FLOAT_EQ(r.floatNumber("a", 9.f), 0.5f);
    EXPECT_FLOAT_EQ(r.floatNumber("absent", 9.f), 9.f);
    EXPECT_TRUE(r.boolean("b", false));
    EXPECT_EQ(r.integer("absent", 4, 0, 10), 4);
    EXPECT_EQ(r.string("absent", "x"), "x");
}

TEST(JsonReader, ShortestDoubleRoundTripsEveryFloat) {
    for (const float f : {575.8f, 0.1f, 1e-7f, 3.4e38f, -2.5f}) {
        const double d = shortestDouble(f);
        EXPECT_EQ(static_cast<float>(d), f) << f;
    }
    EXPECT_EQ(nlohmann::json(shortestDouble(575.8f)).dump(), "575.8");
}

TEST(ReadTextFile, SaysWhatIsWrongWithThePath) {
    const std::filesystem::path dir = test::freshTempDir("read_text_file");
    const auto messageOf = [](const std::filesystem::path& p) {
        try {
            (void)readTextFile(p);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(messageOf(dir / "absent.json").find("does not exist"), std::string::npos);
    EXPECT_NE(messageOf(dir).find("is a folder"), std::string::npos);
    std::filesystem::create_symlink(dir / "loop_b", dir / "loop_a");
    std::filesystem::create_symlink(dir / "loop_a", dir / "loop_b");
    EXPECT_NE(messageOf(dir / "loop_a").find("loop of symbolic links"), std::string::npos);
    std::ofstream(dir / "ok.json") << "{}";
    EXPECT_EQ(readTextFile(dir / "ok.json"), "{}");
}

}  // namespace
}  // namespace meadow
