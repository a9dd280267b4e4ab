#include "archetype_json.h"

#include <array>

namespace meadow::modeling::detail {

using nlohmann::json;

namespace {

constexpr std::array<std::pair<AnalyticShape, const char*>, 4> kShapeNames{{
    {AnalyticShape::Quad, "quad"},
    {AnalyticShape::Triangle, "triangle"},
    {AnalyticShape::Quadratic, "quadratic"},
    {AnalyticShape::TriangleTip, "triangle-tip"},
}};

json vec3ToJson(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

AnalyticShape shapeFromString(const std::string& text, const std::string& path) {
    for (const auto& [shape, name] : kShapeNames)
        if (text == name) return shape;
    throw JsonFieldError(path,
                         "unknown shape '" + text + "' (quad, triangle, quadratic, triangle-tip)");
}

}  // namespace

}  // namespace meadow::modeling::detail

namespace meadow::modeling {

std::string toString(AnalyticShape shape) {
    for (const auto& [s, name] : detail::kShapeNames)
        if (s == shape) return name;
    return "quadratic";
}

namespace detail {

json archetypeToJson(const Archetype& a) {
    json j;
    j["name"] = a.name;
    j["height_m"] = a.height_m();
    j["spine_m"] = {{"v0", vec3ToJson(a.spine_m.v0)},
                    {"v1", vec3ToJson(a.spine_m.v1)},
                    {"v2", vec3ToJson(a.spine_m.v2)}};
    j["width_m"] = a.width.width_m;
    j["nearest_shape"] = toString(a.nearestShape);
    j["tau"] = a.tau;
    return j;
}

Archetype archetypeFromJson(const json& value, const std::string& path) {
    const JsonReader r(value, path);
    Archetype a;
    a.name = r.string("name");
    const JsonReader spine(r.object("spine_m"), r.pathOf("spine_m"));
    a.spine_m = {spine.vec3("v0"), spine.vec3("v1"), spine.vec3("v2")};
    if (a.height_m() <= 0.f) throw JsonFieldError(r.pathOf("spine_m"), "has zero length");
    const json& widths = r.array("width_m");
    if (widths.size() < 2) throw JsonFieldError(r.pathOf("width_m"), "needs at least 2 samples");
    for (std::size_t i = 0; i < widths.size(); ++i) {
        const std::string p = r.pathOf("width_m") + "[" + std::to_string(i) + "]";
        const float w = finiteNumber(widths[i], p);
        if (w < 0.f) throw JsonFieldError(p, "is negative");
        a.width.width_m.push_back(w);
    }
    if (a.width.maxWidth_m() <= 0.f)
        throw JsonFieldError(r.pathOf("width_m"), "is zero everywhere");
    a.nearestShape =
        shapeFromString(r.string("nearest_shape", "quadratic"), r.pathOf("nearest_shape"));
    a.tau = r.number("tau", 0.5f);
    if (a.tau < 0.f || a.tau > 1.f) throw JsonFieldError(r.pathOf("tau"), "must lie in [0, 1]");
    return a;
}

json mergeToJson(const ArchetypeMerge& m) {
    return {{"kept", m.kept}, {"merged", m.merged}, {"shape_distance_m", m.shapeDistance_m}};
}

ArchetypeMerge mergeFromJson(const json& value, const std::string& path) {
    const JsonReader r(value, path);
    ArchetypeMerge m;
    m.kept = r.string("kept");
    for (const json& name : r.array("merged")) {
        if (!name.is_string()) throw JsonFieldError(r.pathOf("merged"), "must hold names");
        m.merged.push_back(name.get<std::string>());
    }
    m.shapeDistance_m = r.number("shape_distance_m", 0.f);
    return m;
}

}  // namespace detail
}  // namespace meadow::modeling
