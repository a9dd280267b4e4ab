#include "archetype_json.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "meadow/core/json_reader.h"

namespace meadow::modeling::detail {

using nlohmann::json;

namespace {

// Frame numbers, blade ids and point counts are ints.
constexpr int kMaxCount = std::numeric_limits<int>::max();
// No blade of grass, nor a bamboo leaf, reaches this far from its root: a larger control point
// or width is another unit or a corrupt file.
constexpr float kMaxBladeExtent_m = 10.f;

json vec3ToJson(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

}  // namespace

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
    j["left_width_fraction"] = a.leftWidthFraction;
    j["twist_at_tip_rad"] = a.twistAtTip_rad;
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
                {"tip_extension_mm", a.fit.tipExtension_mm},
                {"twist_points", a.fit.twistPoints},
                {"base_tilt_deg", a.fit.baseTilt_deg}};
    j["source"] = {{"recording", a.source.recording},
                   {"frame", a.source.frame},
                   {"blade_id", a.source.bladeId},
                   {"flags", a.source.flags},
                   {"seen_in", json::array()}};
    for (const BladeSighting& seen : a.source.seenIn)
        j["source"]["seen_in"].push_back({{"frame", seen.frame}, {"blade_id", seen.bladeId}});
    if (!a.source.alsoSeenIn.empty()) {
        j["source"]["also_seen_in"] = json::array();
        for (const BladeSighting& seen : a.source.alsoSeenIn)
            j["source"]["also_seen_in"].push_back(
                {{"frame", seen.frame}, {"blade_id", seen.bladeId}});
    }
    if (a.source.placed) {
        json m = json::array();
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) m.push_back(a.source.cameraFromBlade[col][row]);
        j["source"]["camera_from_blade_row_major"] = std::move(m);
    }
    j["knots_m"] = json::array();
    for (const glm::vec3& k : a.knots_m) j["knots_m"].push_back(vec3ToJson(k));
    return j;
}

Archetype archetypeFromJson(const json& value, const std::string& path) {
    const JsonReader r(value, path);
    Archetype a;
    a.name = r.string("name");
    const JsonReader spine = r.object("spine_m");
    a.spine_m = {spine.vec3("v0"), spine.vec3("v1"), spine.vec3("v2")};
    for (const char* v : {"v0", "v1", "v2"}) {
        const glm::vec3 p = spine.vec3(v);
        if (std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}) > kMaxBladeExtent_m)
            spine.fail(v, "lies more than " + std::to_string(static_cast<int>(kMaxBladeExtent_m)) +
                              " m from the blade's root: control points are in metres");
    }
    if (a.height_m() <= 0.f) r.fail("spine_m", "has zero length");
    a.width.width_m = r.floatArray("width_m");
    if (a.width.width_m.size() < 2) r.fail("width_m", "needs at least 2 samples");
    for (std::size_t i = 0; i < a.width.width_m.size(); ++i)
        if (a.width.width_m[i] < 0.f || a.width.width_m[i] > kMaxBladeExtent_m)
            throw JsonError(JsonError::Kind::Field, elementPath(r.pathOf("width_m"), i),
                            a.width.width_m[i] < 0.f ? "is negative"
                                                     : "is wider than any blade: widths are in "
                                                       "metres");
    if (a.width.maxWidth_m() <= 0.f) r.fail("width_m", "is zero everywhere");
    const std::string shape = r.string("nearest_shape", "quadratic");
    const std::optional<AnalyticShape> nearest = kAnalyticShapeNames.parse(shape);
    if (!nearest)
        r.fail("nearest_shape",
               "unknown shape '" + shape + "' (" + kAnalyticShapeNames.list() + ")");
    a.nearestShape = *nearest;
    a.tau = r.floatNumber("tau", 0.5f, 0.f, 1.f);
    // Absent in older libraries: symmetric and flat.
    a.leftWidthFraction = r.floatNumber("left_width_fraction", 0.5f, 0.f, 1.f);
    a.twistAtTip_rad =
        r.floatNumber("twist_at_tip_rad", 0.f, -kMaxTwistAtTip_rad, kMaxTwistAtTip_rad);
    // Fit report, source and knots are optional: an authored archetype has none.
    if (r.has("fit")) {
        const JsonReader fit = r.object("fit");
        a.fit.spineRms_mm = fit.floatNumber("spine_rms_mm", 0.f);
        a.fit.spineMax_mm = fit.floatNumber("spine_max_mm", 0.f);
        a.fit.widthMae_mm = fit.floatNumber("width_mae_mm", 0.f);
        a.fit.widthMax_mm = fit.floatNumber("width_max_mm", 0.f);
        a.fit.shapeError_mm = fit.floatNumber("shape_error_mm", 0.f);
        a.fit.widthCheckMae_mm = fit.floatNumber("width_check_mae_mm", 0.f);
        a.fit.sideLengthRatio = fit.floatNumber("side_length_ratio", 1.f);
        const auto length_mm = [&](const char* name) {
            const float v = fit.floatNumber(name, 0.f);
            if (v < 0.f) fit.fail(name, "must not be negative");
            return v;
        };
        a.fit.asymmetric = fit.boolean("asymmetric", false);
        a.fit.skeletonPoints = fit.integer("skeleton_points", 0, 0, kMaxCount);
        // Rooting and tip extension (blade_root.h, blade_tip.h); absent in older libraries.
        a.fit.baseExtension_mm = length_mm("base_extension_mm");
        a.fit.baseNotRooted = fit.boolean("base_not_rooted", false);
        a.fit.tipExtension_mm = length_mm("tip_extension_mm");
        a.fit.twistPoints = fit.integer("twist_points", 0, 0, kMaxCount);  // absent before twist
        a.fit.baseTilt_deg = fit.floatNumber("base_tilt_deg", 0.f, -180.f, 180.f);
    }
    if (r.has("source")) {
        const JsonReader src = r.object("source");
        a.source.recording = src.string("recording", "");
        a.source.frame = src.integer("frame", -1, -1, kMaxCount);
        a.source.bladeId = src.integer("blade_id", 0, 0, kMaxCount);
        if (src.has("flags"))  // absent in older libraries
            for (const json& line : src.array("flags")) {
                if (!line.is_string()) src.fail("flags", "must hold reason lines (strings)");
                a.source.flags.push_back(line.get<std::string>());
            }
        if (src.has("camera_from_blade_row_major")) {  // absent in older libraries
            const std::vector<float> m = src.floatArray("camera_from_blade_row_major");
            if (m.size() != 16)
                src.fail("camera_from_blade_row_major", "needs 16 numbers, row by row");
            for (int row = 0; row < 4; ++row)
                for (int col = 0; col < 4; ++col)
                    a.source.cameraFromBlade[col][row] = m[static_cast<std::size_t>(row * 4 + col)];
            a.source.placed = true;
        }
        // Both absent in older libraries; also_seen_in absent where no view was joined.
        for (const auto& [field, list] :
             {std::pair{"seen_in", &a.source.seenIn}, {"also_seen_in", &a.source.alsoSeenIn}}) {
            if (!src.has(field)) continue;
            const json& seen = src.array(field);
            for (std::size_t i = 0; i < seen.size(); ++i) {
                const std::string at = elementPath(src.pathOf(field), i);
                if (!seen[i].is_object())
                    throw JsonError(JsonError::Kind::Field, at,
                                    "must be an object with frame and blade_id");
                const JsonReader entry(seen[i], at);
                list->push_back({entry.integer("frame", 0, kMaxCount),
                                 entry.integer("blade_id", 0, kMaxCount)});
            }
        }
    }
    if (r.has("knots_m")) {
        const json& knots = r.array("knots_m");
        for (std::size_t i = 0; i < knots.size(); ++i) {
            const std::string at = elementPath(r.pathOf("knots_m"), i);
            if (!knots[i].is_array() || knots[i].size() != 3)
                throw JsonError(JsonError::Kind::Field, at, "must be an array of 3 numbers");
            a.knots_m.push_back({finiteFloat(knots[i][0], elementPath(at, 0)),
                                 finiteFloat(knots[i][1], elementPath(at, 1)),
                                 finiteFloat(knots[i][2], elementPath(at, 2))});
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
        if (!name.is_string()) r.fail("merged", "must hold names");
        m.merged.push_back(name.get<std::string>());
    }
    m.shapeDistance_m = r.floatNumber("shape_distance_m", 0.f);
    return m;
}

}  // namespace meadow::modeling::detail
