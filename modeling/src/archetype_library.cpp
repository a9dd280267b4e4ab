#include "meadow/modeling/archetype_library.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "archetype_json.h"
#include "meadow/capture/atomic_file.h"
#include "meadow/modeling/error.h"

namespace meadow::modeling {

using nlohmann::json;

ArchetypeLibrary parseArchetypeLibrary(const std::string& jsonText, const std::string& origin) {
    const auto fail = [&](const std::string& what) -> ModelingError {
        return ModelingError("archetype library " + origin + ": " + what);
    };
    json doc;
    try {
        doc = json::parse(jsonText);
    } catch (const json::exception& e) {
        // parse_error for broken syntax (NaN and Inf literals too), out_of_range for numbers
        // that overflow a double (1e999).
        throw fail(std::string("not valid JSON (") + e.what() +
                   "); NaN and Inf are not JSON, re-export the library");
    }
    if (!doc.is_object()) throw fail("the top level must be a JSON object");
    const auto format = doc.value("format", std::string{});
    if (format != kArchetypeLibraryFormat)
        throw fail("format is '" + format + "', expected '" + kArchetypeLibraryFormat + "'");
    if (!doc.contains("version") || !doc["version"].is_number_integer())
        throw fail("missing integer 'version'");
    const int version = doc["version"].get<int>();
    if (version != kArchetypeLibraryVersion)
        throw fail("format version " + std::to_string(version) +
                   " is not supported (this meadow reads version " +
                   std::to_string(kArchetypeLibraryVersion) +
                   "); use a matching meadow or re-capture");

    ArchetypeLibrary lib;
    try {
        detail::JsonReader reader(doc);
        lib.generator = reader.string("generator", "unknown");
        lib.source = reader.string("source", "");
        const json& list = reader.array("archetypes");
        if (list.empty())
            throw detail::JsonFieldError("archetypes", "the library has no archetypes");
        for (std::size_t i = 0; i < list.size(); ++i)
            lib.archetypes.push_back(
                detail::archetypeFromJson(list[i], "archetypes[" + std::to_string(i) + "]"));
        if (doc.contains("merges")) {
            const json& merges = reader.array("merges");
            for (std::size_t i = 0; i < merges.size(); ++i)
                lib.merges.push_back(
                    detail::mergeFromJson(merges[i], "merges[" + std::to_string(i) + "]"));
        }
    } catch (const detail::JsonFieldError& e) {
        throw fail(e.what());
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
    return doc.dump(2) + "\n";
}

ArchetypeLibrary loadArchetypeLibrary(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw ModelingError("cannot open archetype library " + path.string() +
                            ": check the path (create one with `meadow capture`)");
    std::stringstream text;
    text << in.rdbuf();
    return parseArchetypeLibrary(text.str(), path.string());
}

void saveArchetypeLibrary(const ArchetypeLibrary& library, const std::filesystem::path& path) {
    if (library.archetypes.empty())
        throw ModelingError("refusing to write " + path.string() +
                            ": the library has no archetypes");
    writeFileAtomically(path, serialiseArchetypeLibrary(library));
}

}  // namespace meadow::modeling
