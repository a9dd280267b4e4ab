#include <cmath>

#include "archetype_json.h"

namespace meadow::modeling::detail {

using nlohmann::json;

JsonReader::JsonReader(const json& object, std::string path)
    : object_(object), path_(std::move(path)) {
    if (!object_.is_object())
        throw JsonFieldError(path_.empty() ? "(top level)" : path_, "must be a JSON object");
}

std::string JsonReader::pathOf(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
}

const json& JsonReader::at(const std::string& key) const {
    const auto it = object_.find(key);
    if (it == object_.end()) throw JsonFieldError(pathOf(key), "missing");
    return *it;
}

float finiteNumber(const json& value, const std::string& path) {
    if (!value.is_number()) throw JsonFieldError(path, "must be a number");
    const double x = value.get<double>();
    if (!std::isfinite(x)) throw JsonFieldError(path, "is NaN or infinite");
    return static_cast<float>(x);
}

std::string JsonReader::string(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_string()) throw JsonFieldError(pathOf(key), "must be a string");
    return v.get<std::string>();
}

std::string JsonReader::string(const std::string& key, const std::string& fallback) const {
    return has(key) ? string(key) : fallback;
}

float JsonReader::number(const std::string& key) const {
    return finiteNumber(at(key), pathOf(key));
}

float JsonReader::number(const std::string& key, float fallback) const {
    return has(key) ? number(key) : fallback;
}

int JsonReader::integer(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_number_integer()) throw JsonFieldError(pathOf(key), "must be an integer");
    return v.get<int>();
}

glm::vec3 JsonReader::vec3(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_array() || v.size() != 3)
        throw JsonFieldError(pathOf(key), "must be an array of 3 numbers");
    return {finiteNumber(v[0], pathOf(key) + "[0]"), finiteNumber(v[1], pathOf(key) + "[1]"),
            finiteNumber(v[2], pathOf(key) + "[2]")};
}

const json& JsonReader::array(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_array()) throw JsonFieldError(pathOf(key), "must be an array");
    return v;
}

const json& JsonReader::object(const std::string& key) const {
    const json& v = at(key);
    if (!v.is_object()) throw JsonFieldError(pathOf(key), "must be an object");
    return v;
}

}  // namespace meadow::modeling::detail
