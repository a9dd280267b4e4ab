#include "meadow/core/json_reader.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <system_error>

namespace meadow {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string withPath(const std::string& path, const std::string& problem) {
    return path.empty() ? problem : path + ": " + problem;
}

// A short decimal for range messages: 0.5, 100, 1e+06.
std::string shortDecimal(double value) {
    std::ostringstream s;
    s << value;
    return s.str();
}

}  // namespace

JsonError::JsonError(Kind kind, std::string path, std::string problem)
    : Error(withPath(path, problem)),
      kind_(kind),
      path_(std::move(path)),
      problem_(std::move(problem)) {}

json parseJsonObject(std::string_view text) {
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {
        // parse_error for broken syntax (NaN and Inf literals too), out_of_range for numbers
        // that overflow a double (1e999).
        throw JsonError(JsonError::Kind::Syntax, "",
                        std::string("not valid JSON (") + e.what() + ")");
    }
    if (!doc.is_object())
        throw JsonError(JsonError::Kind::NotAnObject, "",
                        std::string("must hold a JSON object, got ") + doc.type_name());
    return doc;
}

void checkJsonFormat(const json& root, JsonFormat expected) {
    const std::string wanted = "\"" + std::string(expected.name) + "\"";
    const auto format = root.find("format");
    if (format == root.end())
        throw JsonError(JsonError::Kind::WrongFormat, "", "format is missing, expected " + wanted);
    if (!format->is_string() || format->get<std::string>() != expected.name)
        throw JsonError(JsonError::Kind::WrongFormat, "",
                        "format is " + format->dump() + ", expected " + wanted);
    const auto version = root.find("version");
    if (version == root.end()) throw JsonError(JsonError::Kind::Field, "version", "is missing");
    if (!version->is_number_integer())
        throw JsonError(JsonError::Kind::Field, "version",
                        "must be an integer, got " + version->dump());
    if (version->get<std::int64_t>() != expected.version)
        throw JsonError(JsonError::Kind::WrongVersion, "",
                        "version " + version->dump() +
                            " is not supported (this meadow reads version " +
                            std::to_string(expected.version) + ")");
}

std::string readTextFile(const fs::path& file) {
    std::error_code ec;
    const fs::file_status status = fs::status(file, ec);
    if (ec && ec == std::errc::too_many_symbolic_link_levels)
        throw Error(file.string() + " is a loop of symbolic links: give the file itself");
    if (!fs::exists(status)) throw Error(file.string() + " does not exist");
    if (fs::is_directory(status)) throw Error(file.string() + " is a folder, not a file");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error("cannot read " + file.string() + ": check that it is readable");
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) throw Error("cannot read " + file.string() + ": reading failed part way");
    return text.str();
}

double shortestDouble(float value) {
    char text[32];
    const auto [end, ec] = std::to_chars(std::begin(text), std::end(text), value);
    if (ec != std::errc{}) return value;
    double result = value;
    std::from_chars(text, end, result);
    return result;
}

std::string elementPath(const std::string& path, std::size_t index) {
    return path + "[" + std::to_string(index) + "]";
}

float finiteFloat(const json& value, const std::string& path) {
    if (!value.is_number())
        throw JsonError(JsonError::Kind::Field, path, "must be a number, got " + value.dump());
    const double x = value.get<double>();
    if (!std::isfinite(x)) throw JsonError(JsonError::Kind::Field, path, "is NaN or infinite");
    if (std::abs(x) > std::numeric_limits<float>::max())
        throw JsonError(JsonError::Kind::Field, path, "is too large, got " + value.dump());
    return static_cast<float>(x);
}

JsonReader::JsonReader(const json& object, std::string path)
    : object_(object), path_(std::move(path)) {
    if (!object_.is_object())
        throw JsonError(JsonError::Kind::Field, path_.empty() ? "(top level)" : path_,
                        "must be a JSON object");
}

bool JsonReader::has(std::string_view key) const { return object_.contains(key); }

std::string JsonReader::pathOf(std::string_view key) const {
    if (key.empty()) return path_;
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void JsonReader::fail(std::string_view key, const std::string& problem) const {
    throw JsonError(JsonError::Kind::Field, pathOf(key), problem);
}

const json& JsonReader::at(std::string_view key) const {
    const auto it = object_.find(key);
    if (it == object_.end()) fail(key, "is missing");
    return *it;
}

std::string JsonReader::string(std::string_view key) const {
    const json& v = at(key);
    if (!v.is_string()) fail(key, "must be a string, got " + v.dump());
    return v.get<std::string>();
}

double JsonReader::number(std::string_view key) const {
    const json& v = at(key);
    if (!v.is_number()) fail(key, "must be a number, got " + v.dump());
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(key, "is NaN or infinite");
    return x;
}

float JsonReader::floatNumber(std::string_view key) const {
    return finiteFloat(at(key), pathOf(key));
}

std::int64_t JsonReader::integer(std::string_view key) const {
    const json& v = at(key);
    if (v.is_number_unsigned() &&
        v.get<std::uint64_t>() >
            static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        fail(key, "is too large, got " + v.dump());
    if (!v.is_number_integer()) fail(key, "must be an integer, got " + v.dump());
    return v.get<std::int64_t>();
}

bool JsonReader::boolean(std::string_view key) const {
    const json& v = at(key);
    if (!v.is_boolean()) fail(key, "must be true or false, got " + v.dump());
    return v.get<bool>();
}

glm::vec3 JsonReader::vec3(std::string_view key) const {
    const json& v = at(key);
    if (!v.is_array() || v.size() != 3) fail(key, "must be an array of 3 numbers");
    const std::string p = pathOf(key);
    return {finiteFloat(v[0], elementPath(p, 0)), finiteFloat(v[1], elementPath(p, 1)),
            finiteFloat(v[2], elementPath(p, 2))};
}

const json& JsonReader::array(std::string_view key) const {
    const json& v = at(key);
    if (!v.is_array()) fail(key, "must be an array");
    return v;
}

JsonReader JsonReader::object(std::string_view key) const {
    const json& v = at(key);
    if (!v.is_object()) fail(key, "must be an object");
    return JsonReader(v, pathOf(key));
}

std::vector<float> JsonReader::floatArray(std::string_view key) const {
    const json& values = array(key);
    const std::string p = pathOf(key);
    std::vector<float> out;
    out.reserve(values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
        out.push_back(finiteFloat(values[i], elementPath(p, i)));
    return out;
}

std::string JsonReader::string(std::string_view key, const std::string& fallback) const {
    return has(key) ? string(key) : fallback;
}

float JsonReader::floatNumber(std::string_view key, float fallback) const {
    return has(key) ? floatNumber(key) : fallback;
}

bool JsonReader::boolean(std::string_view key, bool fallback) const {
    return has(key) ? boolean(key) : fallback;
}

glm::vec3 JsonReader::vec3(std::string_view key, glm::vec3 fallback) const {
    return has(key) ? vec3(key) : fallback;
}

float JsonReader::floatNumber(std::string_view key, float fallback, float min, float max) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    if (!v.is_number()) fail(key, "must be a number, got " + v.dump());
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < min || x > max)
        fail(key,
             "must lie in [" + shortDecimal(min) + ", " + shortDecimal(max) + "], got " + v.dump());
    return static_cast<float>(x);
}

int JsonReader::integer(std::string_view key, int fallback, int min, int max) const {
    return has(key) ? integer(key, min, max) : fallback;
}

int JsonReader::integer(std::string_view key, int min, int max) const {
    const std::int64_t n = integer(key);
    if (n < min || n > max)
        fail(key, "must lie in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " +
                      std::to_string(n));
    return static_cast<int>(n);
}

glm::vec2 JsonReader::range(std::string_view key, glm::vec2 fallback, float min, float max) const {
    if (!has(key)) return fallback;
    const json& v = at(key);
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
        fail(key, "must be [min, max], got " + v.dump());
    const glm::vec2 r{finiteFloat(v[0], elementPath(pathOf(key), 0)),
                      finiteFloat(v[1], elementPath(pathOf(key), 1))};
    if (!(r.x <= r.y) || r.x < min || r.y > max)
        fail(key, "must be [min, max] with min <= max within [" + shortDecimal(min) + ", " +
                      shortDecimal(max) + "], got " + v.dump());
    return r;
}

void JsonReader::onlyKeys(std::initializer_list<std::string_view> allowed) const {
    for (const auto& [key, value] : object_.items()) {
        bool known = false;
        for (const std::string_view a : allowed) known = known || key == a;
        if (!known) fail(key, "unknown field");
    }
}

}  // namespace meadow
