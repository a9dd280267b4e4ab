#pragma once
// The one way meadow reads its JSON files (recordings, synth truth, archetype libraries,
// scenes): parse one object, check its format name and version, then read every field through
// a JsonReader that checks type, finiteness and range and names the field's path on failure
// ("archetypes[3].width_m[2]: is NaN or infinite"). Readers catch JsonError and rethrow it as
// their layer's error with the file's name and what the user can do.
#include <cstdint>
#include <filesystem>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "meadow/core/error.h"

namespace meadow {

// What a file says it is: {"format": name, "version": version, ...}.
struct JsonFormat {
    std::string_view name;
    int version = 0;
};

class JsonError : public Error {
public:
    enum class Kind {
        Syntax,        // not JSON at all (NaN and Inf literals, numbers beyond a double)
        NotAnObject,   // the top level is not an object
        WrongFormat,   // "format" is missing or names another format
        WrongVersion,  // "version" is another version
        Field,         // a field is missing, of the wrong type or out of range
    };
    // what() is "<path>: <problem>", or the problem alone when path is empty.
    JsonError(Kind kind, std::string path, std::string problem);
    [[nodiscard]] Kind kind() const { return kind_; }
    [[nodiscard]] const std::string& path() const { return path_; }
    [[nodiscard]] const std::string& problem() const { return problem_; }

private:
    Kind kind_;
    std::string path_;
    std::string problem_;
};

// One JSON object parsed from text; JsonError Syntax or NotAnObject otherwise.
[[nodiscard]] nlohmann::json parseJsonObject(std::string_view text);

// WrongFormat unless root["format"] is expected.name, WrongVersion unless root["version"] is
// expected.version (Field when the version is not an integer).
void checkJsonFormat(const nlohmann::json& root, JsonFormat expected);

// The whole file as text. Throws meadow::Error naming the path when it does not exist, is a
// folder, is a symbolic-link loop or cannot be read.
[[nodiscard]] std::string readTextFile(const std::filesystem::path& file);

// Typed, checked access to one JSON object; `path` prefixes every error's field path.
class JsonReader {
public:
    // JsonError Field ("must be a JSON object") when `object` is not one.
    explicit JsonReader(const nlohmann::json& object, std::string path = "");
    // The reader keeps a reference: a temporary would leave it dangling.
    JsonReader(nlohmann::json&&, std::string = "") = delete;

    [[nodiscard]] bool has(std::string_view key) const;
    [[nodiscard]] std::string pathOf(std::string_view key) const;
    [[nodiscard]] const std::string& path() const { return path_; }
    [[nodiscard]] const nlohmann::json& node() const { return object_; }
    // Throws JsonError Field at pathOf(key) (this object's own path when key is empty).
    [[noreturn]] void fail(std::string_view key, const std::string& problem) const;

    // Required fields: "is missing" when absent, then a type check.
    [[nodiscard]] const nlohmann::json& at(std::string_view key) const;
    [[nodiscard]] std::string string(std::string_view key) const;
    [[nodiscard]] double number(std::string_view key) const;      // finite
    [[nodiscard]] float floatNumber(std::string_view key) const;  // finite, within a float
    [[nodiscard]] std::int64_t integer(std::string_view key) const;
    [[nodiscard]] int integer(std::string_view key, int min, int max) const;  // within [min, max]
    [[nodiscard]] bool boolean(std::string_view key) const;
    [[nodiscard]] glm::vec3 vec3(std::string_view key) const;
    [[nodiscard]] const nlohmann::json& array(std::string_view key) const;
    [[nodiscard]] JsonReader object(std::string_view key) const;
    [[nodiscard]] std::vector<float> floatArray(std::string_view key) const;

    // Optional fields: the fallback when absent, checked like the required ones when present.
    [[nodiscard]] std::string string(std::string_view key, const std::string& fallback) const;
    [[nodiscard]] float floatNumber(std::string_view key, float fallback) const;
    [[nodiscard]] bool boolean(std::string_view key, bool fallback) const;
    [[nodiscard]] glm::vec3 vec3(std::string_view key, glm::vec3 fallback) const;
    // ... and within [min, max] ("must lie in [min, max], got value").
    [[nodiscard]] float floatNumber(std::string_view key, float fallback, float min,
                                    float max) const;
    [[nodiscard]] int integer(std::string_view key, int fallback, int min, int max) const;
    // A [lo, hi] pair with lo <= hi inside [min, max].
    [[nodiscard]] glm::vec2 range(std::string_view key, glm::vec2 fallback, float min,
                                  float max) const;

    // Rejects keys the format does not define: a typo must not fall back to a default.
    void onlyKeys(std::initializer_list<std::string_view> allowed) const;

private:
    const nlohmann::json& object_;
    std::string path_;
};

// `value` as a finite float (within a float's range), or JsonError Field at `path`.
[[nodiscard]] float finiteFloat(const nlohmann::json& value, const std::string& path);
// The float's shortest decimal, as a double: JSON then shows 575.8, not 575.7999877929688, and
// reading it back into a float gives the same float (files round trip bit for bit).
[[nodiscard]] double shortestDouble(float value);
// "<path>[<index>]"
[[nodiscard]] std::string elementPath(const std::string& path, std::size_t index);

}  // namespace meadow
