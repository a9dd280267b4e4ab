#pragma once
// The archetype library: the product of capture, the input of the renderer. On disk it is a
// versioned JSON file (docs/formats.md#archetype-library), optionally with a glTF 2.0 .glb
// holding one mesh per archetype for DCC tools.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "meadow/modeling/archetype.h"

namespace meadow::modeling {

inline constexpr std::string_view kArchetypeLibraryFormat = "meadow.archetype-library";
inline constexpr int kArchetypeLibraryVersion = 1;

// A record that archetypes were merged as near-duplicates (--max-archetypes).
struct ArchetypeMerge {
    std::string kept;                 // name of the archetype that stands for the group
    std::vector<std::string> merged;  // names folded into it
    float shapeDistance_m = 0.f;      // largest shape distance inside the group
};

// The plant's stem, when capture cut its leaves from one (--partition stem-graph).
struct StemMeasure {
    float height_m = 0.f;  // the median over the segmentations that saw it, foot to top node
    int views = 0;         // how many segmentations saw it
};

struct ArchetypeLibrary {
    std::string generator = "meadow";  // what wrote it (e.g. "meadow capture 0.1.0")
    std::string source;                // where the blades came from (recording path, preset)
    std::vector<Archetype> archetypes;
    std::vector<ArchetypeMerge> merges;
    std::optional<StemMeasure> stem;  // optional in the file
};

// Throws ModelingError naming the file and the first problem: not JSON, wrong format name,
// unknown version, a missing field, NaN/Inf or out-of-range values, an empty library.
ArchetypeLibrary loadArchetypeLibrary(const std::filesystem::path& jsonPath);
// Written atomically: a failed write leaves any previous file untouched.
void saveArchetypeLibrary(const ArchetypeLibrary& library, const std::filesystem::path& jsonPath);

// Parse / serialise without files (the loader and writer use these).
ArchetypeLibrary parseArchetypeLibrary(const std::string& jsonText, const std::string& origin);
// Whether `path` is a JSON file of the archetype library format (any version): what a capture
// may replace. False for anything unreadable.
bool isArchetypeLibraryFile(const std::filesystem::path& path);

std::string serialiseArchetypeLibrary(const ArchetypeLibrary& library);

}  // namespace meadow::modeling
