// The `meadow synth` driver: preset -> frames through the simulated sensor -> recording + truth.
#include "meadow/modeling/synthesize.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "archetype_json.h"
#include "meadow/capture/atomic_file.h"
#include "meadow/capture/recording.h"
#include "meadow/capture/simulated_sensor.h"
#include "meadow/modeling/error.h"

namespace meadow::modeling {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kTruthFolderName = "truth";
constexpr const char* kTruthFileName = "blades.json";
constexpr const char* kLabelsFolderName = "labels";
constexpr float kMaxNoiseScale = 10.f;
// Label images are mostly 0: the slowest, smallest PNG setting costs little here.
constexpr int kLabelPngCompression = 9;

std::string frameName(int index) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d.png", index);
    return name;
}

// The float's shortest decimal, as a double: JSON then shows "0.1", not 0.10000000149011612,
// and reading it back into a float gives the same float.
double tidy(float value) {
    char text[32];
    const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
    if (ec != std::errc{}) return value;
    double out = value;
    std::from_chars(text, end, out);
    return out;
}

json vecJson(const glm::vec3& v) { return json::array({tidy(v.x), tidy(v.y), tidy(v.z)}); }

json bladeJson(const SynthTruthBlade& b) {
    json widths = json::array(), fractions = json::array();
    for (float w : b.width_m) widths.push_back(tidy(w));
    for (float s : b.widthFraction) fractions.push_back(tidy(s));
    return {{"id", b.id},
            {"archetype", b.archetype},
            {"height_m", tidy(b.height_m)},
            {"spine_camera_m",
             {{"v0", vecJson(b.spineCamera_m.v0)},
              {"v1", vecJson(b.spineCamera_m.v1)},
              {"v2", vecJson(b.spineCamera_m.v2)}}},
            {"width_profile", {{"s", fractions}, {"width_m", widths}}},
            {"left_width_fraction", tidy(b.leftWidthFraction)},
            {"twist_at_tip_rad", tidy(b.twistAtTip_rad)},
            {"face_normal_camera", vecJson(b.faceNormalCamera)}};
}

std::vector<float> floatArray(const json& array, const std::string& path) {
    if (!array.is_array()) throw detail::JsonFieldError(path, "must be an array");
    std::vector<float> out;
    for (std::size_t i = 0; i < array.size(); ++i)
        out.push_back(detail::finiteNumber(array[i], path + "[" + std::to_string(i) + "]"));
    return out;
}

SynthTruthBlade bladeFromJson(const json& value, const std::string& path) {
    const detail::JsonReader r(value, path);
    SynthTruthBlade b;
    b.id = r.integer("id");
    if (b.id < 1 || b.id > 65535)
        throw detail::JsonFieldError(r.pathOf("id"), "must be a label in [1, 65535]");
    b.archetype = r.string("archetype");
    b.height_m = r.number("height_m");
    const detail::JsonReader spine(r.object("spine_camera_m"), r.pathOf("spine_camera_m"));
    b.spineCamera_m = {spine.vec3("v0"), spine.vec3("v1"), spine.vec3("v2")};
    const detail::JsonReader profile(r.object("width_profile"), r.pathOf("width_profile"));
    b.widthFraction = floatArray(profile.array("s"), profile.pathOf("s"));
    b.width_m = floatArray(profile.array("width_m"), profile.pathOf("width_m"));
    if (b.widthFraction.size() != b.width_m.size() || b.width_m.size() < 2)
        throw detail::JsonFieldError(r.pathOf("width_profile"),
                                     "needs s and width_m of the same length, at least 2");
    b.leftWidthFraction = r.number("left_width_fraction");
    b.twistAtTip_rad = r.number("twist_at_tip_rad");
    b.faceNormalCamera = r.vec3("face_normal_camera");
    return b;
}

json intrinsicsJson(const capture::Intrinsics& k) {
    return {{"width_px", k.width_px}, {"height_px", k.height_px}, {"fx_px", tidy(k.fx_px)},
            {"fy_px", tidy(k.fy_px)}, {"cx_px", tidy(k.cx_px)},   {"cy_px", tidy(k.cy_px)}};
}

// Names the truth folder may hold, so clearing it never deletes anything else.
bool isTruthFolder(const fs::path& folder) {
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name == kLabelsFolderName && it->is_directory(ec)) {
            for (fs::directory_iterator f(it->path(), ec); !ec && f != end; f.increment(ec))
                if (!capture::isFrameFileName(f->path().filename().string())) return false;
        } else if (!isFileOrItsTemporary(name, kTruthFileName)) {
            return false;
        }
    }
    return !ec;
}

// A previous synth run left OUT/truth beside the recording; RecordingWriter only accepts a
// folder holding a recording, so the old truth goes first, if it is only truth.
void clearOldTruth(const fs::path& out) {
    const fs::path truth = out / kTruthFolderName;
    std::error_code ec;
    if (!fs::exists(truth, ec)) return;
    // Only beside a recording: in any other folder RecordingWriter refuses, and the truth stays.
    for (fs::directory_iterator it(out, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name != "depth" && name != kTruthFolderName &&
            !isFileOrItsTemporary(name, "recording.json"))
            return;
    }
    if (!fs::is_directory(truth, ec) || !isTruthFolder(truth))
        throw ModelingError("refusing to overwrite " + truth.string() +
                            ": it holds files meadow synth did not write; choose another "
                            "--out folder or remove it first");
    fs::remove_all(truth, ec);
    if (ec)
        throw ModelingError("cannot clear the old truth in " + truth.string() + ": " +
                            ec.message() + "; check permissions or remove it by hand");
}

void writeLabels(const fs::path& file, const cv::Mat1w& labels) {
    std::vector<unsigned char> bytes;
    if (!cv::imencode(".png", labels, bytes, {cv::IMWRITE_PNG_COMPRESSION, kLabelPngCompression}))
        throw ModelingError("cannot encode the label image " + file.string() +
                            " as PNG: check the OpenCV build has PNG support");
    writeFileAtomically(
        file, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

}  // namespace

bool operator==(const SynthTruthBlade& a, const SynthTruthBlade& b) {
    return a.id == b.id && a.archetype == b.archetype && a.height_m == b.height_m &&
           a.spineCamera_m.v0 == b.spineCamera_m.v0 && a.spineCamera_m.v1 == b.spineCamera_m.v1 &&
           a.spineCamera_m.v2 == b.spineCamera_m.v2 && a.widthFraction == b.widthFraction &&
           a.width_m == b.width_m && a.leftWidthFraction == b.leftWidthFraction &&
           a.twistAtTip_rad == b.twistAtTip_rad && a.faceNormalCamera == b.faceNormalCamera;
}

bool operator==(const SynthTruthFrame& a, const SynthTruthFrame& b) {
    return a.index == b.index && a.timestamp_s == b.timestamp_s && a.labels == b.labels &&
           a.blades == b.blades;
}

bool operator==(const SynthTruth& a, const SynthTruth& b) {
    return a.preset == b.preset && a.seed == b.seed && a.noiseScale == b.noiseScale &&
           a.sensorNoiseScale == b.sensorNoiseScale && a.distance_m == b.distance_m &&
           a.cameraTilt_rad == b.cameraTilt_rad && a.intrinsics == b.intrinsics &&
           a.cameraFromWorld == b.cameraFromWorld && a.frames == b.frames;
}

SynthTruthFrame truthOfFrame(const SyntheticTuft& tuft, int frameIndex) {
    SynthTruthFrame frame;
    frame.index = frameIndex;
    frame.timestamp_s = tuft.timestamp_s;
    frame.labels = std::string(kLabelsFolderName) + "/" + frameName(frameIndex);
    for (const SyntheticBlade& blade : tuft.blades) {
        SynthTruthBlade b;
        b.id = blade.id;
        b.archetype = blade.archetype.name;
        b.height_m = blade.archetype.height_m();
        b.spineCamera_m = blade.spineInCamera_m();
        const std::size_t n = blade.archetype.width.width_m.size();
        b.width_m = blade.archetype.width.width_m;
        for (std::size_t i = 0; i < n; ++i)
            b.widthFraction.push_back(n < 2 ? 0.f : static_cast<float>(i) / (n - 1));
        b.leftWidthFraction = blade.mesh.leftWidthFraction;
        b.twistAtTip_rad = blade.mesh.twistAtTip_rad;
        const glm::mat3 rotation(blade.cameraFromBlade);
        const TriangleMesh local = bladeMesh(blade.archetype, blade.mesh);
        b.faceNormalCamera = glm::normalize(rotation * local.normals.front());
        frame.blades.push_back(std::move(b));
    }
    return frame;
}

std::string synthTruthToJson(const SynthTruth& truth) {
    json cameraFromWorld = json::array();
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            cameraFromWorld.push_back(tidy(truth.cameraFromWorld[col][row]));
    json frames = json::array();
    for (const SynthTruthFrame& f : truth.frames) {
        json blades = json::array();
        for (const SynthTruthBlade& b : f.blades) blades.push_back(bladeJson(b));
        frames.push_back({{"index", f.index},
                          {"timestamp_s", f.timestamp_s},
                          {"labels", f.labels},
                          {"blades", std::move(blades)}});
    }
    const json doc = {{"format", kSynthTruthFormatName},
                      {"version", kSynthTruthFormatVersion},
                      {"preset", truth.preset},
                      {"seed", truth.seed},
                      {"noise_scale", tidy(truth.noiseScale)},
                      {"sensor_noise_scale", tidy(truth.sensorNoiseScale)},
                      {"distance_m", tidy(truth.distance_m)},
                      {"camera_tilt_rad", tidy(truth.cameraTilt_rad)},
                      {"intrinsics", intrinsicsJson(truth.intrinsics)},
                      {"camera_from_world_row_major", std::move(cameraFromWorld)},
                      {"frames", std::move(frames)}};
    return doc.dump(1) + "\n";
}

SynthTruth parseSynthTruth(std::string_view text, const std::string& sourceName) {
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::parse_error& e) {
        throw ModelingError(sourceName + " is not valid JSON (" + e.what() +
                            "); regenerate it with meadow synth");
    }
    try {
        const detail::JsonReader r(doc);
        const std::string format = r.string("format");
        if (format != kSynthTruthFormatName)
            throw ModelingError(sourceName + " is a '" + format + "' file, not " +
                                std::string(kSynthTruthFormatName) +
                                ": pass the truth/blades.json that meadow synth wrote");
        const int version = r.integer("version");
        if (version != kSynthTruthFormatVersion)
            throw ModelingError(sourceName + " has " + std::string(kSynthTruthFormatName) +
                                " version " + std::to_string(version) + "; this meadow reads " +
                                "version " + std::to_string(kSynthTruthFormatVersion) +
                                ": regenerate it or update meadow");
        SynthTruth t;
        t.preset = r.string("preset");
        const json& seed = doc.at("seed");
        if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<long long>() >= 0))
            throw detail::JsonFieldError("seed", "must be a non-negative integer");
        t.seed = seed.get<std::uint64_t>();
        t.noiseScale = r.number("noise_scale");
        t.sensorNoiseScale = r.number("sensor_noise_scale");
        t.distance_m = r.number("distance_m");
        t.cameraTilt_rad = r.number("camera_tilt_rad");
        const detail::JsonReader k(r.object("intrinsics"), "intrinsics");
        t.intrinsics = {k.integer("width_px"), k.integer("height_px"), k.number("fx_px"),
                        k.number("fy_px"),     k.number("cx_px"),      k.number("cy_px")};
        if (const std::string problem = t.intrinsics.problem(); !problem.empty())
            throw detail::JsonFieldError("intrinsics", problem);
        const std::vector<float> m =
            floatArray(r.array("camera_from_world_row_major"), "camera_from_world_row_major");
        if (m.size() != 16)
            throw detail::JsonFieldError("camera_from_world_row_major", "must hold 16 numbers");
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) t.cameraFromWorld[col][row] = m[4 * row + col];
        const json& frames = r.array("frames");
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const std::string path = "frames[" + std::to_string(i) + "]";
            const detail::JsonReader f(frames[i], path);
            SynthTruthFrame frame;
            frame.index = f.integer("index");
            // A double, unlike the float fields: read it whole, not through JsonReader::number.
            const json& stamp = frames[i].at("timestamp_s");
            if (!stamp.is_number() || !std::isfinite(stamp.get<double>()))
                throw detail::JsonFieldError(f.pathOf("timestamp_s"), "must be a finite number");
            frame.timestamp_s = stamp.get<double>();
            frame.labels = f.string("labels");
            const json& blades = f.array("blades");
            for (std::size_t j = 0; j < blades.size(); ++j)
                frame.blades.push_back(
                    bladeFromJson(blades[j], path + ".blades[" + std::to_string(j) + "]"));
            t.frames.push_back(std::move(frame));
        }
        return t;
    } catch (const detail::JsonFieldError& e) {
        throw ModelingError(sourceName + ": " + e.what() + "; regenerate it with meadow synth");
    } catch (const json::exception& e) {
        throw ModelingError(sourceName + ": " + e.what() + "; regenerate it with meadow synth");
    }
}

SynthTruth readSynthTruth(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in)
        throw ModelingError("cannot read " + file.string() +
                            ": check the path (meadow synth writes OUT/truth/blades.json)");
    std::stringstream text;
    text << in.rdbuf();
    return parseSynthTruth(text.str(), file.string());
}

std::uint64_t synthFrameSeed(std::uint64_t seed, std::uint64_t frame) {
    std::uint64_t z = seed + 0x9e3779b97f4a7c15ull * (frame + 1);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

SynthTruth synthesize(const SynthOptions& options,
                      const std::function<void(int done, int total)>& progress) {
    const SynthPreset* preset = findSynthPreset(options.preset);
    if (!preset)
        throw ModelingError("unknown preset '" + options.preset +
                            "'; known presets: " + synthPresetNames());
    if (options.frames < 1 || options.frames > kMaxSynthFrames)
        throw std::invalid_argument("synthesize: frames must be in [1, " +
                                    std::to_string(kMaxSynthFrames) + "], got " +
                                    std::to_string(options.frames));
    if (!(options.noiseScale >= 0.f && options.noiseScale <= kMaxNoiseScale))
        throw std::invalid_argument("synthesize: noise scale must be in [0, " +
                                    std::to_string(kMaxNoiseScale) + "], got " +
                                    std::to_string(options.noiseScale));

    TuftParams params;
    params.seed = options.seed;
    params.distance_m = options.distance_m;
    params.bladeCount = options.bladeCount;
    const TuftSpec spec = buildPresetSpec(*preset, params);

    capture::NoiseModel noise;
    noise.scale = options.noiseScale * preset->noiseMultiplier;
    const capture::SimulatedSensor sensor(spec.camera.intrinsics, noise);

    SynthTruth truth;
    truth.preset = preset->name;
    truth.seed = options.seed;
    truth.noiseScale = options.noiseScale;
    truth.sensorNoiseScale = noise.scale;
    truth.distance_m = spec.camera.distance_m;
    truth.cameraTilt_rad = spec.camera.tilt_rad;
    truth.intrinsics = spec.camera.intrinsics;
    truth.cameraFromWorld = spec.camera.cameraFromWorld();

    clearOldTruth(options.out);
    capture::RecordingInfo info;
    info.sensor = "meadow synth (simulated Kinect v1, preset " + preset->name + ")";
    info.intrinsics = spec.camera.intrinsics;
    info.frameRate_hz = kSynthFrameRate_hz;
    capture::RecordingWriter writer(options.out, info);
    const fs::path truthFolder = options.out / kTruthFolderName;

    TuftSpec frameSpec = spec;
    frameSpec.wind.frameRate_hz = static_cast<float>(kSynthFrameRate_hz);
    for (int i = 0; i < options.frames; ++i) {
        const SyntheticTuft tuft = buildTuft(frameSpec, i);
        const capture::SimulatedFrame frame = sensor.render(
            tuft.meshes(), synthFrameSeed(options.seed, static_cast<std::uint64_t>(i)));
        writer.write(frame.depth_mm);
        SynthTruthFrame frameTruth = truthOfFrame(tuft, i);
        writeLabels(truthFolder / frameTruth.labels, frame.labels);
        truth.frames.push_back(std::move(frameTruth));
        if (progress) progress(i + 1, options.frames);
    }
    writeFileAtomically(truthFolder / kTruthFileName, synthTruthToJson(truth));
    writer.finish();
    return truth;
}

}  // namespace meadow::modeling
