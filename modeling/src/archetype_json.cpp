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
    j["fit"] = {{"spine_rms_mm", a.fit.spineRms_mm},
                {"spine_max_mm", a.fit.spineMax_mm},
                {"width_mae_mm", a.fit.widthMae_mm},
                {"width_max_mm", a.fit.widthMax_mm},
                {"shape_error_mm", a.fit.shapeError_mm},
                {"width_check_mae_mm", a.fit.widthCheckMae_mm},
                {"side_length_ratio", a.fit.sideLengthRatio},
                {"asymmetric", a.fit.asymmetric},
                {"skeleton_points", a.fit.skeletonPoints},
                {"base_extension_mm", a.fit.baseExtension_mm},
                {"base_not_rooted", a.fit.baseNotRooted},
                {"tip_extension_mm", a.fit.tipExtension_mm}};
    j["source"] = {{"recording", a.source.recording},
                   {"frame", a.source.frame},
                   {"blade_id", a.source.bladeId},
                   {"flags", a.source.flags},
                   {"seen_in", json::array()}};
    for (const BladeSighting& seen : a.source.seenIn)
        j["source"]["seen_in"].push_back({{"frame", seen.frame}, {"blade_id", seen.bladeId}});
    j["knots_m"] = json::array();
    for (const glm::vec3& k : a.knots_m) j["knots_m"].push_back(vec3ToJson(k));
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
    // Fit report, source and knots are optional: an authored archetype has none.
    if (r.has("fit")) {
        const JsonReader fit(r.object("fit"), r.pathOf("fit"));
        a.fit.spineRms_mm = fit.number("spine_rms_mm", 0.f);
        a.fit.spineMax_mm = fit.number("spine_max_mm", 0.f);
        a.fit.widthMae_mm = fit.number("width_mae_mm", 0.f);
        a.fit.widthMax_mm = fit.number("width_max_mm", 0.f);
        a.fit.shapeError_mm = fit.number("shape_error_mm", 0.f);
        a.fit.widthCheckMae_mm = fit.number("width_check_mae_mm", 0.f);
        a.fit.sideLengthRatio = fit.number("side_length_ratio", 1.f);
        const auto flag = [&](const char* name) {
            if (!fit.has(name)) return false;
            const json& value = r.object("fit")[name];
            if (!value.is_boolean())
                throw JsonFieldError(fit.pathOf(name), "must be true or false");
            return value.get<bool>();
        };
        const auto length_mm = [&](const char* name) {
            const float v = fit.number(name, 0.f);
            if (v < 0.f) throw JsonFieldError(fit.pathOf(name), "must not be negative");
            return v;
        };
        a.fit.asymmetric = flag("asymmetric");
        a.fit.skeletonPoints = fit.has("skeleton_points") ? fit.integer("skeleton_points") : 0;
        // Rooting and tip extension (blade_root.h, blade_tip.h); absent in older libraries.
        a.fit.baseExtension_mm = length_mm("base_extension_mm");
        a.fit.baseNotRooted = flag("base_not_rooted");
        a.fit.tipExtension_mm = length_mm("tip_extension_mm");
    }
    if (r.has("source")) {
        const JsonReader src(r.object("source"), r.pathOf("source"));
        a.source.recording = src.string("recording", "");
        a.source.frame = src.has("frame") ? src.integer("frame") : -1;
        a.source.bladeId = src.has("blade_id") ? src.integer("blade_id") : 0;
        if (src.has("flags"))  // absent in older libraries
            for (const json& line : src.array("flags")) {
                if (!line.is_string())
                    throw JsonFieldError(src.pathOf("flags"), "must hold reason lines (strings)");
                a.source.flags.push_back(line.get<std::string>());
            }
        if (src.has("seen_in")) {  // absent in older libraries
            const json& seen = src.array("seen_in");
            for (std::size_t i = 0; i < seen.size(); ++i) {
                const std::string path = src.pathOf("seen_in") + "[" + std::to_string(i) + "]";
                if (!seen[i].is_object())
                    throw JsonFieldError(path, "must be an object with frame and blade_id");
                const JsonReader entry(seen[i], path);
                a.source.seenIn.push_back({entry.integer("frame"), entry.integer("blade_id")});
            }
        }
    }
    if (r.has("knots_m")) {
        const json& knots = r.array("knots_m");
        for (std::size_t i = 0; i < knots.size(); ++i) {
            const std::string p = r.pathOf("knots_m") + "[" + std::to_string(i) + "]";
            if (!knots[i].is_array() || knots[i].size() != 3)
                throw JsonFieldError(p, "must be an array of 3 numbers");
            a.knots_m.push_back({finiteNumber(knots[i][0], p), finiteNumber(knots[i][1], p),
                                 finiteNumber(knots[i][2], p)});
        }
    }
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
