#pragma once
// JSON <-> Archetype, with every value checked (type, finiteness, range) and every failure
// naming the field's path, e.g. "archetypes[3].width_m[2] is NaN or infinite".
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "meadow/modeling/archetype_library.h"

namespace meadow::modeling::detail {

class JsonFieldError : public std::runtime_error {
public:
    JsonFieldError(const std::string& path, const std::string& what)
        : std::runtime_error(path + ": " + what) {}
};

// Typed, checked access to one JSON object; `path` prefixes every error.
class JsonReader {
public:
    explicit JsonReader(const nlohmann::json& object, std::string path = "");
    [[nodiscard]] std::string string(const std::string& key) const;
    [[nodiscard]] std::string string(const std::string& key, const std::string& fallback) const;
    [[nodiscard]] float number(const std::string& key) const;  // finite
    [[nodiscard]] float number(const std::string& key, float fallback) const;
    [[nodiscard]] int integer(const std::string& key) const;
    [[nodiscard]] glm::vec3 vec3(const std::string& key) const;
    [[nodiscard]] const nlohmann::json& array(const std::string& key) const;
    [[nodiscard]] const nlohmann::json& object(const std::string& key) const;
    [[nodiscard]] bool has(const std::string& key) const { return object_.contains(key); }
    [[nodiscard]] std::string pathOf(const std::string& key) const;

private:
    const nlohmann::json& at(const std::string& key) const;
    const nlohmann::json& object_;
    std::string path_;
};

float finiteNumber(const nlohmann::json& value, const std::string& path);

nlohmann::json archetypeToJson(const Archetype& archetype);
Archetype archetypeFromJson(const nlohmann::json& value, const std::string& path);
nlohmann::json mergeToJson(const ArchetypeMerge& merge);
ArchetypeMerge mergeFromJson(const nlohmann::json& value, const std::string& path);

}  // namespace meadow::modeling::detail
