#pragma once
// JSON <-> Archetype, with every value checked (type, finiteness, range) and every failure
// naming the field's path, e.g. "archetypes[3].width_m[2] is NaN or infinite".
#include <nlohmann/json.hpp>
#include <string>

#include "meadow/modeling/archetype_library.h"

namespace meadow::modeling::detail {

nlohmann::json archetypeToJson(const Archetype& archetype);
Archetype archetypeFromJson(const nlohmann::json& value, const std::string& path);
nlohmann::json mergeToJson(const ArchetypeMerge& merge);
ArchetypeMerge mergeFromJson(const nlohmann::json& value, const std::string& path);

}  // namespace meadow::modeling::detail
