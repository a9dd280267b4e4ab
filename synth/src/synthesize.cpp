// The `meadow synth` driver: preset -> frames through the simulated sensor -> recording + truth.
#include "meadow/synth/synthesize.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "meadow/capture/recording.h"
#include "meadow/core/atomic_file.h"
#include "meadow/core/json_reader.h"
#include "meadow/core/random.h"
#include "meadow/core/staged_folder.h"
#include "meadow/synth/error.h"
#include "meadow/synth/simulated_sensor.h"
#include "truth_folder.h"

namespace meadow::synth {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kTruthFileName = "blades.json";
constexpr float kMaxNoiseScale = 10.f;

double tidy(float value) { return shortestDouble(value); }

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

SynthTruthBlade bladeFromJson(const json& value, const std::string& path) {
    const JsonReader r(value, path);
    SynthTruthBlade b;
    b.id = r.integer("id", 1, 65535);
    b.archetype = r.string("archetype");
    b.height_m = r.floatNumber("height_m");
    const JsonReader spine = r.object("spine_camera_m");
    b.spineCamera_m = {spine.vec3("v0"), spine.vec3("v1"), spine.vec3("v2")};
    const JsonReader profile = r.object("width_profile");
    b.widthFraction = profile.floatArray("s");
    b.width_m = profile.floatArray("width_m");
    if (b.widthFraction.size() != b.width_m.size() || b.width_m.size() < 2)
        r.fail("width_profile", "needs s and width_m of the same length, at least 2");
    b.leftWidthFraction = r.floatNumber("left_width_fraction");
    b.twistAtTip_rad = r.floatNumber("twist_at_tip_rad");
    b.faceNormalCamera = r.vec3("face_normal_camera");
    return b;
}

json intrinsicsJson(const capture::Intrinsics& k) {
    return {{"width_px", k.width_px}, {"height_px", k.height_px}, {"fx_px", tidy(k.fx_px)},
            {"fy_px", tidy(k.fy_px)}, {"cx_px", tidy(k.cx_px)},   {"cy_px", tidy(k.cy_px)}};
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
    frame.labels = detail::labelsPath(frameIndex);
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
        b.leftWidthFraction = blade.archetype.leftWidthFraction;
        b.twistAtTip_rad = blade.archetype.twistAtTip_rad;
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
    try {
        const json doc = parseJsonObject(text);
        checkJsonFormat(doc, {kSynthTruthFormatName, kSynthTruthFormatVersion});
        const JsonReader r(doc);
        SynthTruth t;
        t.preset = r.string("preset");
        const json& seed = r.at("seed");
        if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<long long>() >= 0))
            r.fail("seed", "must be a non-negative integer");
        t.seed = seed.get<std::uint64_t>();
        t.noiseScale = r.floatNumber("noise_scale");
        t.sensorNoiseScale = r.floatNumber("sensor_noise_scale");
        t.distance_m = r.floatNumber("distance_m");
        t.cameraTilt_rad = r.floatNumber("camera_tilt_rad");
        const JsonReader k = r.object("intrinsics");
        constexpr int kMaxSide_px = 1 << 16;
        t.intrinsics = {k.integer("width_px", 1, kMaxSide_px),
                        k.integer("height_px", 1, kMaxSide_px),
                        k.floatNumber("fx_px"),
                        k.floatNumber("fy_px"),
                        k.floatNumber("cx_px"),
                        k.floatNumber("cy_px")};
        if (const std::string problem = t.intrinsics.problem(); !problem.empty())
            r.fail("intrinsics", problem);
        const std::vector<float> m = r.floatArray("camera_from_world_row_major");
        if (m.size() != 16) r.fail("camera_from_world_row_major", "must hold 16 numbers");
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) t.cameraFromWorld[col][row] = m[4 * row + col];
        const json& frames = r.array("frames");
        for (std::size_t i = 0; i < frames.size(); ++i) {
            const JsonReader f(frames[i], elementPath("frames", i));
            SynthTruthFrame frame;
            frame.index = f.integer("index", 0, kMaxSynthFrames);
            frame.timestamp_s = f.number("timestamp_s");  // a double, unlike the float fields
            frame.labels = f.string("labels");
            const json& blades = f.array("blades");
            for (std::size_t j = 0; j < blades.size(); ++j)
                frame.blades.push_back(
                    bladeFromJson(blades[j], elementPath(f.pathOf("blades"), j)));
            t.frames.push_back(std::move(frame));
        }
        return t;
    } catch (const JsonError& e) {
        const char* hint = e.kind() == JsonError::Kind::WrongFormat
                               ? ": pass the truth/blades.json that meadow synth wrote"
                           : e.kind() == JsonError::Kind::WrongVersion
                               ? ": regenerate it or update meadow"
                               : "; regenerate it with meadow synth";
        throw SynthError(sourceName + ": " + e.what() + hint);
    }
}

SynthTruth readSynthTruth(const fs::path& file) {
    std::string text;
    try {
        text = readTextFile(file);
    } catch (const Error& e) {
        throw SynthError(std::string(e.what()) +
                         ": check the path (meadow synth writes OUT/truth/blades.json)");
    }
    return parseSynthTruth(text, file.string());
}

std::uint64_t synthFrameSeed(std::uint64_t seed, std::uint64_t frame) {
    std::uint64_t state = seed + 0x9E3779B97F4A7C15ull * frame;  // SplitMix64's Weyl step
    return splitMix64(state);
}

SynthTruth synthesize(const SynthOptions& options,
                      const std::function<void(int done, int total)>& progress) {
    const SynthPreset* preset = findSynthPreset(options.preset);
    if (!preset)
        throw SynthError("unknown preset '" + options.preset +
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

    synth::NoiseModel noise;
    noise.scale = options.noiseScale * preset->noiseMultiplier;
    const synth::SimulatedSensor sensor(spec.camera.intrinsics, noise);

    SynthTruth truth;
    truth.preset = preset->name;
    truth.seed = options.seed;
    truth.noiseScale = options.noiseScale;
    truth.sensorNoiseScale = noise.scale;
    truth.distance_m = spec.camera.distance_m;
    truth.cameraTilt_rad = spec.camera.tilt_rad;
    truth.intrinsics = spec.camera.intrinsics;
    truth.cameraFromWorld = spec.camera.cameraFromWorld();

    // The new recording and its truth are written beside the old ones and replace them whole
    // when complete: a run that fails or is interrupted leaves the old ones as they were.
    detail::checkReplaceableSynthOutput(options.out);
    StagedFolder staged(options.out);
    capture::RecordingInfo info;
    info.sensor = "meadow synth (simulated Kinect v1, preset " + preset->name + ")";
    info.intrinsics = spec.camera.intrinsics;
    info.frameRate_hz = kSynthFrameRate_hz;
    capture::RecordingWriter writer(staged.path(), info);
    const fs::path truthFolder = staged.path() / detail::kTruthFolderName;

    TuftSpec frameSpec = spec;
    frameSpec.wind.frameRate_hz = static_cast<float>(kSynthFrameRate_hz);
    for (int i = 0; i < options.frames; ++i) {
        const SyntheticTuft tuft = buildTuft(frameSpec, i);
        const synth::SimulatedFrame frame = sensor.render(
            tuft.meshes(), synthFrameSeed(options.seed, static_cast<std::uint64_t>(i)));
        writer.write(frame.depth_mm);
        SynthTruthFrame frameTruth = truthOfFrame(tuft, i);
        detail::writeLabels(truthFolder / frameTruth.labels, frame.labels);
        truth.frames.push_back(std::move(frameTruth));
        if (progress) progress(i + 1, options.frames);
    }
    writeFileAtomically(truthFolder / kTruthFileName, synthTruthToJson(truth));
    writer.finish();
    staged.commit();
    return truth;
}

}  // namespace meadow::synth
