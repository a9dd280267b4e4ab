#include "meadow/modeling/archetype_library.h"

#include <nlohmann/json.hpp>

#include "archetype_json.h"
#include "meadow/core/atomic_file.h"
#include "meadow/core/json_reader.h"
#include "meadow/modeling/error.h"

namespace meadow::modeling {

using nlohmann::json;

namespace {
// No plant a depth camera frames has a taller stem: a larger value is a unit mistake.
constexpr float kMaxStemHeight_m = 10.f;
}  // namespace

ArchetypeLibrary parseArchetypeLibrary(const std::string& jsonText, const std::string& origin) {
    const std::string where = "archetype library " + origin + ": ";
    ArchetypeLibrary lib;
    try {
        const json doc = parseJsonObject(jsonText);
        checkJsonFormat(doc, {kArchetypeLibraryFormat, kArchetypeLibraryVersion});
        const JsonReader reader(doc);
        lib.generator = reader.string("generator", "unknown");
        lib.source = reader.string("source", "");
        const json& list = reader.array("archetypes");
        if (list.empty()) reader.fail("archetypes", "the library has no archetypes");
        for (std::size_t i = 0; i < list.size(); ++i)
            lib.archetypes.push_back(
                detail::archetypeFromJson(list[i], elementPath("archetypes", i)));
        if (reader.has("merges")) {
            const json& merges = reader.array("merges");
            for (std::size_t i = 0; i < merges.size(); ++i)
                lib.merges.push_back(detail::mergeFromJson(merges[i], elementPath("merges", i)));
        }
        if (reader.has("stem")) {
            const JsonReader stem = reader.object("stem");
            const float height = stem.floatNumber("height_m");
            if (height < 0.f || height > kMaxStemHeight_m)
                stem.fail("height_m", "must lie in [0, " + std::to_string(kMaxStemHeight_m) +
                                          "] m, got " + std::to_string(height));
            lib.stem = StemMeasure{height, stem.integer("views", 1, 1 << 30)};
        }
    } catch (const JsonError& e) {
        switch (e.kind()) {
            case JsonError::Kind::Syntax:
                throw ModelingError(where + e.what() +
                                    "; NaN and Inf are not JSON, re-export the library");
            case JsonError::Kind::WrongFormat:
                throw ModelingError(where + e.what() + ": this is not an archetype library");
            case JsonError::Kind::WrongVersion:
                throw ModelingError(where + e.what() + "; use a matching meadow or re-capture");
            case JsonError::Kind::NotAnObject:
            case JsonError::Kind::Field:
                break;
        }
        throw ModelingError(where + e.what() + "; fix that field or capture the library again");
    }
    return lib;
}

std::string serialiseArchetypeLibrary(const ArchetypeLibrary& lib) {
    json doc;
    doc["format"] = kArchetypeLibraryFormat;
    doc["version"] = kArchetypeLibraryVersion;
    doc["units"] = "metres; angles in radians";
    doc["frame"] =
        "blade-local: v0 at the origin, +Y up along the base, face in the XY plane, bend toward +X";
    doc["generator"] = lib.generator;
    doc["source"] = lib.source;
    doc["archetypes"] = json::array();
    for (const Archetype& a : lib.archetypes)
        doc["archetypes"].push_back(detail::archetypeToJson(a));
    doc["merges"] = json::array();
    for (const ArchetypeMerge& m : lib.merges) doc["merges"].push_back(detail::mergeToJson(m));
    if (lib.stem) doc["stem"] = {{"height_m", lib.stem->height_m}, {"views", lib.stem->views}};
    return doc.dump(2) + "\n";
}

bool isArchetypeLibraryFile(const std::filesystem::path& path) {
    try {
        const json doc = parseJsonObject(readTextFile(path));
        const auto format = doc.find("format");
        return format != doc.end() && format->is_string() &&
               format->get<std::string>() == kArchetypeLibraryFormat;
    } catch (const std::exception&) {
        return false;
    }
}

ArchetypeLibrary loadArchetypeLibrary(const std::filesystem::path& path) {
    std::string text;
    try {
        text = readTextFile(path);
    } catch (const Error& e) {
        throw ModelingError("cannot open archetype library: " + std::string(e.what()) +
                            "; check the path (create one with `meadow capture`)");
    }
    return parseArchetypeLibrary(text, path.string());
}

void saveArchetypeLibrary(const ArchetypeLibrary& library, const std::filesystem::path& path) {
    if (library.archetypes.empty())
        throw ModelingError("refusing to write " + path.string() +
                            ": the library has no archetypes");
    writeFileAtomically(path, serialiseArchetypeLibrary(library));
}

}  // namespace meadow::modeling
