// "meadow.plant-truth" version 1 (docs/formats.md, "Plant truth").
#include <nlohmann/json.hpp>

#include "meadow/core/json_reader.h"
#include "meadow/synth/error.h"
#include "meadow/synth/plant_synthesize.h"

namespace meadow::synth {

using nlohmann::json;

namespace {

double tidy(float value) { return shortestDouble(value); }
json vecJson(const glm::vec3& v) { return json::array({tidy(v.x), tidy(v.y), tidy(v.z)}); }

json matrixJson(const glm::mat4& m) {
    json out = json::array();
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) out.push_back(tidy(m[col][row]));
    return out;
}

glm::mat4 matrixFromJson(const JsonReader& r, const char* key) {
    const std::vector<float> v = r.floatArray(key);
    if (v.size() != 16) r.fail(key, "needs 16 numbers, row by row");
    glm::mat4 m(1.f);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) m[col][row] = v[static_cast<std::size_t>(row * 4 + col)];
    return m;
}

json organJson(const PlantTruthOrgan& o) {
    json line = json::array();
    for (const glm::vec3& p : o.centreLineCamera_m) line.push_back(vecJson(p));
    return {{"id", o.id},
            {"source_label", o.sourceLabel},
            {"stem", o.stem},
            {"centre_line_camera_m", std::move(line)},
            {"length_m", tidy(o.length_m)},
            {"max_width_m", tidy(o.maxWidth_m)},
            {"visible_pixels", o.visiblePixels},
            {"visible_share", tidy(o.visibleShare)}};
}

PlantTruthOrgan organFromJson(const json& value, const std::string& path) {
    const JsonReader r(value, path);
    PlantTruthOrgan o;
    o.id = r.integer("id", 1, 65000);
    o.sourceLabel = r.integer("source_label", 0, 1000000);
    o.stem = r.boolean("stem");
    for (const json& p : r.array("centre_line_camera_m")) {
        if (!p.is_array() || p.size() != 3)
            r.fail("centre_line_camera_m", "holds [x, y, z] points");
        o.centreLineCamera_m.emplace_back(finiteFloat(p[0], path), finiteFloat(p[1], path),
                                          finiteFloat(p[2], path));
    }
    o.length_m = r.floatNumber("length_m");
    o.maxWidth_m = r.floatNumber("max_width_m");
    o.visiblePixels = r.integer("visible_pixels", 0, 1 << 30);
    o.visibleShare = r.floatNumber("visible_share", 0.f, 0.f, 1.f);
    return o;
}

json intrinsicsJson(const capture::Intrinsics& k) {
    return {{"width_px", k.width_px}, {"height_px", k.height_px}, {"fx_px", tidy(k.fx_px)},
            {"fy_px", tidy(k.fy_px)}, {"cx_px", tidy(k.cx_px)},   {"cy_px", tidy(k.cy_px)}};
}

}  // namespace

std::string plantTruthToJson(const PlantTruth& t) {
    json views = json::array();
    for (const PlantTruthView& v : t.views) {
        json organs = json::array();
        for (const PlantTruthOrgan& o : v.organs) organs.push_back(organJson(o));
        views.push_back({{"index", v.index},
                         {"azimuth_deg", tidy(v.azimuth_deg)},
                         {"labels", v.labels},
                         {"camera_from_world_row_major", matrixJson(v.cameraFromWorld)},
                         {"organs", std::move(organs)}});
    }
    const PlantViewOptions& o = t.options;
    const json doc = {{"format", kPlantTruthFormatName},
                      {"version", kPlantTruthFormatVersion},
                      {"plant", t.plant},
                      {"source", t.source},
                      {"unit", t.unit},
                      {"stem_found_by", t.stemFoundBy},
                      {"sensor", t.sensor},
                      {"noise_scale", tidy(t.noiseScale)},
                      {"intrinsics", intrinsicsJson(t.intrinsics)},
                      {"camera",
                       {{"distance_m", tidy(o.distance_m)},
                        {"pitch_deg", tidy(o.pitch_deg)},
                        {"aim_height_m", tidy(o.aimHeight_m)},
                        {"views", o.views},
                        {"scenery", o.scenery},
                        {"wall_behind_m", tidy(o.wallBehind_m)},
                        {"seed", o.seed}}},
                      {"labels",
                       {{"floor", kFloorLabel},
                        {"wall", kWallLabel},
                        {"pot", kPotLabel},
                        {"clutter", kClutterLabel}}},
                      {"views", std::move(views)}};
    return doc.dump(1) + "\n";
}

PlantTruth parsePlantTruth(std::string_view text, const std::string& sourceName) {
    try {
        const json doc = parseJsonObject(text);
        checkJsonFormat(doc, {kPlantTruthFormatName, kPlantTruthFormatVersion});
        const JsonReader r(doc);
        PlantTruth t;
        t.plant = r.string("plant");
        t.source = r.string("source", "");
        t.unit = r.string("unit", "");
        t.stemFoundBy = r.string("stem_found_by", "");
        t.sensor = r.string("sensor", "");
        t.noiseScale = r.floatNumber("noise_scale", 1.f, 0.f, 100.f);
        const JsonReader k = r.object("intrinsics");
        t.intrinsics.width_px = k.integer("width_px", 1, 16384);
        t.intrinsics.height_px = k.integer("height_px", 1, 16384);
        t.intrinsics.fx_px = k.floatNumber("fx_px");
        t.intrinsics.fy_px = k.floatNumber("fy_px");
        t.intrinsics.cx_px = k.floatNumber("cx_px");
        t.intrinsics.cy_px = k.floatNumber("cy_px");
        const JsonReader c = r.object("camera");
        t.options.distance_m = c.floatNumber("distance_m");
        t.options.pitch_deg = c.floatNumber("pitch_deg");
        t.options.aimHeight_m = c.floatNumber("aim_height_m", -1.f);
        t.options.views = c.integer("views", 1, 360);
        t.options.scenery = c.boolean("scenery", true);
        t.options.wallBehind_m = c.floatNumber("wall_behind_m", 0.6f);
        const json& views = r.array("views");
        for (std::size_t i = 0; i < views.size(); ++i) {
            const std::string at = elementPath("views", i);
            const JsonReader v(views[i], at);
            PlantTruthView view;
            view.index = v.integer("index", 0, 1 << 30);
            view.azimuth_deg = v.floatNumber("azimuth_deg", 0.f);
            view.labels = v.string("labels");
            view.cameraFromWorld = matrixFromJson(v, "camera_from_world_row_major");
            const json& organs = v.array("organs");
            for (std::size_t j = 0; j < organs.size(); ++j)
                view.organs.push_back(organFromJson(organs[j], elementPath(at + ".organs", j)));
            t.views.push_back(std::move(view));
        }
        return t;
    } catch (const JsonError& e) {
        throw SynthError(sourceName + ": " + e.what() +
                         (e.kind() == JsonError::Kind::WrongFormat
                              ? ": pass the truth/plant.json that meadow synth --plant wrote"
                              : "; regenerate it with meadow synth --plant"));
    }
}

PlantTruth readPlantTruth(const std::filesystem::path& file) {
    std::string text;
    try {
        text = readTextFile(file);
    } catch (const Error& e) {
        throw SynthError(std::string(e.what()) +
                         ": check the path (meadow synth --plant writes OUT/truth/plant.json)");
    }
    return parsePlantTruth(text, file.string());
}

}  // namespace meadow::synth
