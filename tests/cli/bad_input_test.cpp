// Bad and hostile input to every verb, as a user would give it: each case sets up its files in a
// scratch folder (corrupt files are made here, not committed), runs the real binary, and holds
// it to meadow's rule for user errors: exit status 2, one line starting "meadow: " that names
// the file or option at fault, every earlier output intact byte for byte, and no temporary
// left behind. Cases are grouped by the class of defect they guard against.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <string>
#include <vector>

#include "cli/cli_test_util.h"
#include "meadow/capture/recording.h"
#include "meadow/modeling/archetype_library.h"
#include "support/scene_files.h"

namespace meadow::test {
namespace {

namespace fs = std::filesystem;

// --- Inputs -----------------------------------------------------------------------------------

// A 64 x 48 recording of `frames` frames of noise at 0.5-1.5 m: readable, nothing to capture.
fs::path writeNoiseRecording(const fs::path& folder, int frames = 2) {
    capture::RecordingInfo info;
    info.sensor = "test";
    info.intrinsics = {.width_px = 64,
                       .height_px = 48,
                       .fx_px = 58.f,
                       .fy_px = 58.f,
                       .cx_px = 31.5f,
                       .cy_px = 23.5f};
    capture::RecordingWriter writer(folder, info);
    std::mt19937 rng(5);
    for (int i = 0; i < frames; ++i) {
        cv::Mat1w depth_mm(48, 64);
        for (auto& d : depth_mm) d = static_cast<std::uint16_t>(500 + rng() % 1000);
        writer.write(depth_mm);
    }
    writer.finish();
    return folder;
}

// The synthetic quadratic-leaf tuft: a recording capture models.
fs::path writeTuft(const fs::path& folder) {
    const auto r = runMeadow("synth --preset quadratic-leaf --frames 3 --out " + folder.string());
    if (r.exitCode != 0) ADD_FAILURE() << r.output;
    return folder;
}

std::string readAll(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void writeText(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
}

// The recording's JSON with one field replaced.
void editRecordingJson(const fs::path& folder, const std::string& key, const nlohmann::json& v) {
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(readAll(folder / "recording.json"));
    j[key] = v;
    writeText(folder / "recording.json", j.dump(2));
}

// A library file as a previous capture left it.
fs::path writeLibrary(const fs::path& file, float tipX_m = 0.01f) {
    modeling::Archetype a;
    a.name = "leaf";
    a.spine_m = {{0, 0, 0}, {0, 0.05f, 0}, {tipX_m, 0.1f, 0}};
    a.width.width_m = {0.01f, 0.005f};
    modeling::ArchetypeLibrary library;
    library.archetypes.push_back(a);
    writeText(file, modeling::serialiseArchetypeLibrary(library));
    return file;
}

fs::path writeScene(const fs::path& dir, const nlohmann::json& extra = nlohmann::json::object()) {
    runtime::test::writeQuad(dir / "ground.gltf", -0.5f, 0.5f, -0.5f, 0.5f);
    return runtime::test::writeScene(dir, runtime::test::minimalScene("ground.gltf", extra));
}

// Every regular file under `root` (or `root` itself) with its bytes.
std::map<std::string, std::string> snapshot(const fs::path& root) {
    std::map<std::string, std::string> files;
    std::error_code ec;
    if (fs::is_regular_file(root, ec)) {
        files[root.string()] = readAll(root);
        return files;
    }
    if (!fs::is_directory(root, ec)) return files;
    for (const auto& e : fs::recursive_directory_iterator(root, ec))
        if (e.is_regular_file()) files[e.path().string()] = readAll(e.path());
    return files;
}

bool anyTemporary(const fs::path& root) {
    std::error_code ec;
    for (const auto& e : fs::recursive_directory_iterator(root, ec))
        if (e.path().filename().string().find(".tmp.") != std::string::npos) return true;
    return false;
}

// --- Cases ------------------------------------------------------------------------------------

struct BadInput {
    std::string name;
    // Makes the inputs in `dir` and returns the arguments of `meadow`.
    std::function<std::string(const fs::path& dir)> setup;
    std::vector<std::string> mentions;  // each must appear in the one line
    std::vector<std::string> keep;      // paths under dir that must survive byte for byte
};

std::string str(const fs::path& p) { return p.string(); }

std::vector<BadInput> cases() {
    std::vector<BadInput> c;
    // 1. Outputs that cannot be written: one line before anything is asked of a library
    //    (OpenNI2's recorder crashed on such a path).
    c.push_back({"ConvertToAFolderItCannotWrite",
                 [](const fs::path& d) {
                     return "convert " + str(writeNoiseRecording(d / "rec")) + " /sys/x.oni";
                 },
                 {"/sys/x.oni", "writable"},
                 {"rec"}});
    c.push_back({"ConvertToAMissingDeviceFolder",
                 [](const fs::path& d) {
                     return "convert " + str(writeNoiseRecording(d / "rec")) +
                            " /proc/self/none/x.oni";
                 },
                 {"x.oni"},
                 {"rec"}});
    c.push_back({"CaptureLibraryIntoAFolderItCannotWrite",
                 [](const fs::path& d) {
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out /sys/l.json";
                 },
                 {"/sys/l.json"},
                 {"rec"}});
    c.push_back({"CaptureGlbIntoAFolderItCannotWrite",
                 [](const fs::path& d) {
                     writeLibrary(d / "lib.json");
                     return "capture " + str(writeTuft(d / "rec")) + " --out " +
                            str(d / "lib.json") + " --glb /sys/l.glb";
                 },
                 {"/sys/l.glb"},
                 {"rec", "lib.json"}});
    c.push_back({"SynthIntoAFolderItCannotWrite",
                 [](const fs::path&) { return std::string("synth --preset thin --out /sys/rec"); },
                 {"/sys/rec"},
                 {}});
    c.push_back({"RenderIntoAFolderItCannotWrite",
                 [](const fs::path& d) { return "render " + str(writeScene(d)) + " --out /sys/r"; },
                 {"/sys/r"},
                 {"scene.json"}});
    // 2. A run never destroys its own input or another output.
    c.push_back({"CaptureLibraryOverItsOwnRecordingJson",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     return "capture " + str(rec) + " --out " + str(rec / "recording.json");
                 },
                 {"recording.json", "--out", "not an archetype library"},
                 {"rec"}});
    c.push_back({"CaptureLibraryOverAFrame",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     return "capture " + str(rec) + " --out " + str(rec / "depth" / "000000.png");
                 },
                 {"000000.png", "--out"},
                 {"rec"}});
    c.push_back({"CaptureLibraryAndGlbToTheSameFile",
                 [](const fs::path& d) {
                     writeLibrary(d / "x.json");
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "x.json") + " --glb " + str(d / "x.json");
                 },
                 {"--out/--glb", "x.json"},
                 {"rec", "x.json"}});
    c.push_back({"CaptureLibraryOverAFileOfTheUsers",
                 [](const fs::path& d) {
                     writeText(d / "notes.json", "{\"mine\": true}");
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "notes.json");
                 },
                 {"notes.json", "not an archetype library"},
                 {"rec", "notes.json"}});
    c.push_back({"CaptureLibraryOverAFolder",
                 [](const fs::path& d) {
                     fs::create_directories(d / "lib.json");
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "lib.json");
                 },
                 {"lib.json", "folder"},
                 {"rec"}});
    c.push_back({"CaptureGlbOverAGlbOfSomeoneElse",
                 [](const fs::path& d) {
                     writeText(d / "model.glb", std::string("glTF\x02\0\0\0", 8) + "other");
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "lib.json") + " --glb " + str(d / "model.glb");
                 },
                 {"model.glb", "--glb"},
                 {"rec", "model.glb"}});
    c.push_back({"CaptureOverlaysIntoAFolderOfTheUsers",
                 [](const fs::path& d) {
                     writeText(d / "photos" / "holiday.png", "png");
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "lib.json") + " --debug " + str(d / "photos");
                 },
                 {"photos", "--debug", "holiday.png"},
                 {"rec", "photos"}});
    c.push_back({"CaptureThatFindsNoBladeKeepsThePreviousLibrary",
                 [](const fs::path& d) {
                     writeLibrary(d / "lib.json");
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "lib.json");
                 },
                 {"no blade"},
                 {"rec", "lib.json"}});
    c.push_back({"SynthOverAFolderOfTheUsers",
                 [](const fs::path& d) {
                     writeText(d / "mine" / "thesis.tex", "chapter 1");
                     return "synth --preset thin --out " + str(d / "mine");
                 },
                 {"mine", "not a meadow recording"},
                 {"mine"}});
    c.push_back({"SynthOverATruthFolderHoldingOtherFiles",
                 [](const fs::path& d) {
                     writeTuft(d / "rec");
                     writeText(d / "rec" / "truth" / "notes.txt", "mine");
                     return "synth --preset thin --out " + str(d / "rec");
                 },
                 {"truth", "notes.txt"},
                 {"rec"}});
    c.push_back({"RenderOverAFolderOfTheUsers",
                 [](const fs::path& d) {
                     writeText(d / "out" / "report.pdf", "pdf");
                     return "render " + str(writeScene(d)) + " --out " + str(d / "out");
                 },
                 {"out", "report.pdf"},
                 {"out", "scene.json"}});
    c.push_back({"RenderOverAFile",
                 [](const fs::path& d) {
                     writeText(d / "out", "a file");
                     return "render " + str(writeScene(d)) + " --out " + str(d / "out");
                 },
                 {"out", "file"},
                 {"out"}});
    c.push_back({"ConvertOniOverAFolderOfTheUsers",
                 [](const fs::path& d) {
                     writeText(d / "mine" / "a.txt", "mine");
                     writeText(d / "x.oni", "not really");
                     return "convert " + str(d / "x.oni") + " " + str(d / "mine");
                 },
                 {"mine"},
                 {"mine", "x.oni"}});
    // 4. NaN and infinities in options and files are user errors naming the option or field.
    for (const auto& [option, value] : std::vector<std::pair<std::string, std::string>>{
             {"--noise", "nan"}, {"--noise", "inf"}, {"--distance", "nan"}, {"--distance", "-inf"}})
        c.push_back(
            {std::string("SynthOption") + (option == "--noise" ? "Noise" : "Distance") +
                 (value == "nan" ? "NaN" : "Infinite") + (value.starts_with("-") ? "Negative" : ""),
             [option, value](const fs::path& d) {
                 return "synth --preset thin --out " + str(d / "rec") + " " + option + " " + value;
             },
             {option},
             {}});
    for (const auto& [option, name] :
         std::vector<std::pair<std::string, std::string>>{{"--near", "Near"},
                                                          {"--far", "Far"},
                                                          {"--edge-smoothing", "EdgeSmoothing"},
                                                          {"--tolerance-mm", "Tolerance"}})
        c.push_back({"CaptureOption" + name + "NaN",
                     [option](const fs::path& d) {
                         return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                                str(d / "l.json") + " " + option + " nan";
                     },
                     {option},
                     {"rec"}});
    c.push_back({"SceneNumberBeyondADouble",
                 [](const fs::path& d) {
                     const fs::path scene = writeScene(d);
                     std::string text = readAll(scene);
                     text.replace(text.find("200"), 3, "1e400");
                     writeText(scene, text);
                     return "render " + str(scene) + " --out " + str(d / "r");
                 },
                 {"scene.json", "not valid JSON"},
                 {"scene.json"}});
    c.push_back({"SceneNaNLiteral",
                 [](const fs::path& d) {
                     const fs::path scene = writeScene(d);
                     std::string text = readAll(scene);
                     text.replace(text.find("200"), 3, "NaN");
                     writeText(scene, text);
                     return "render " + str(scene) + " --out " + str(d / "r");
                 },
                 {"scene.json", "not valid JSON"},
                 {"scene.json"}});
    c.push_back({"RecordingFocalLengthBeyondADouble",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     std::string text = readAll(rec / "recording.json");
                     text.replace(text.find("\"fx_px\": 58"), 11, "\"fx_px\": 1e999");
                     writeText(rec / "recording.json", text);
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"recording.json", "not valid JSON"},
                 {"rec"}});
    c.push_back({"LibraryNaN",
                 [](const fs::path& d) {
                     std::string text = readAll(writeLibrary(d / "lib.json"));
                     text.replace(text.find("\"tau\": ") + 7, 3, "NaN");
                     writeText(d / "lib.json", text);
                     return "render " + str(writeScene(d)) + " --library " + str(d / "lib.json") +
                            " --out " + str(d / "r");
                 },
                 {"lib.json"},
                 {"lib.json"}});
    // 5. Values no camera, blade or scene can have: refused with what to do, not modelled.
    c.push_back({"RecordingFocalLengthOfNoCamera",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     editRecordingJson(rec, "fx_px", 1e30);
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"recording.json", "fx_px", "field of view"},
                 {"rec"}});
    c.push_back({"RecordingPrincipalPointFarOutsideTheImage",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     editRecordingJson(rec, "cx_px", 1e30);
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"recording.json", "cx_px", "outside"},
                 {"rec"}});
    c.push_back({"RecordingImageLargerThanAnyCamera",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     editRecordingJson(rec, "width_px", 100000);
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"recording.json", "100000"},
                 {"rec"}});
    c.push_back({"PlainFolderIntrinsicsOfNoCamera",
                 [](const fs::path& d) {
                     fs::create_directories(d / "png");
                     cv::imwrite(str(d / "png" / "0.png"), cv::Mat1w(48, 64, std::uint16_t{900}));
                     return "capture " + str(d / "png") + " --out " + str(d / "l.json") +
                            " --intrinsics 1e30,1e30,31.5,23.5 --depth-unit mm";
                 },
                 {"--intrinsics", "fx_px"},
                 {"png"}});
    c.push_back({"BitRotatedDepthFrames",
                 [](const fs::path& d) {
                     capture::RecordingInfo info;
                     info.intrinsics = {.width_px = 64,
                                        .height_px = 48,
                                        .fx_px = 58.f,
                                        .fy_px = 58.f,
                                        .cx_px = 31.5f,
                                        .cy_px = 23.5f};
                     capture::RecordingWriter writer(d / "rec", info);
                     // SUN RGB-D's PNGs hold depth rotated right by 3 bits: read as
                     // millimetres, the low bits of a depth become tens of metres.
                     std::mt19937 rng(3);
                     cv::Mat1w rotated(48, 64);
                     for (auto& v : rotated) {
                         const unsigned d_mm = 500 + rng() % 1000;
                         v = static_cast<std::uint16_t>((d_mm >> 3) | ((d_mm & 7u) << 13));
                     }
                     writer.write(rotated);
                     writer.finish();
                     return "capture " + str(d / "rec") + " --out " + str(d / "l.json");
                 },
                 {"rec", "frame 0", "--depth-unit"},
                 {"rec"}});
    c.push_back({"LibraryControlPointsLightYearsAway",
                 [](const fs::path& d) {
                     writeLibrary(d / "lib.json", 1e30f);
                     return "render " + str(writeScene(d)) + " --library " + str(d / "lib.json") +
                            " --out " + str(d / "r");
                 },
                 {"lib.json", "v2"},
                 {"lib.json"}});
    c.push_back({"LibraryBladeWiderThanAnyBlade",
                 [](const fs::path& d) {
                     nlohmann::json j =
                         nlohmann::json::parse(readAll(writeLibrary(d / "lib.json")));
                     j["archetypes"][0]["width_m"] = {5e6, 0.005};
                     writeText(d / "lib.json", j.dump());
                     return "render " + str(writeScene(d)) + " --library " + str(d / "lib.json") +
                            " --out " + str(d / "r");
                 },
                 {"lib.json", "width_m"},
                 {"lib.json"}});
    c.push_back({"SceneCameraFarBeyondAnyScene",
                 [](const fs::path& d) {
                     return "render " +
                            str(writeScene(d, {{"camera", {{"position_m", {1e30, 1, 1}}}}})) +
                            " --out " + str(d / "r");
                 },
                 {"scene.json", "camera.position_m"},
                 {"scene.json"}});
    c.push_back({"SceneColliderFarBeyondAnyScene",
                 [](const fs::path& d) {
                     return "render " +
                            str(writeScene(d, {{"colliders", {{{"center_m", {0, -1e9, 0}}}}}})) +
                            " --out " + str(d / "r");
                 },
                 {"scene.json", "colliders[0].center_m"},
                 {"scene.json"}});
    c.push_back(
        {"SceneMeshInMillimetres",
         [](const fs::path& d) {
             runtime::test::writeQuad(d / "ground.gltf", -5e5f, 5e5f, -5e5f, 5e5f);
             return "render " +
                    str(runtime::test::writeScene(d, runtime::test::minimalScene("ground.gltf"))) +
                    " --out " + str(d / "r");
         },
         {"ground.gltf", "metres"},
         {"scene.json"}});
    // 6. Scenes larger than the machine: refused before anything is allocated.
    c.push_back({"SceneWithMoreBladesThanMemory",
                 [](const fs::path& d) {
                     runtime::test::writeQuad(d / "ground.gltf", -5e4f, 5e4f, -5e4f, 5e4f);
                     return "render " +
                            str(runtime::test::writeScene(
                                d, runtime::test::minimalScene(
                                       "ground.gltf", {{"blades", {{"density_per_m2", 1e4}}}}))) +
                            " --out " + str(d / "r");
                 },
                 {"scene.json", "density_per_m2", "memory"},
                 {"scene.json"}});
    // 7. What libraries say reaches the user folded into the one line.
    c.push_back({"CorruptFrameSaysWhatLibpngSaid",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     std::string png = readAll(rec / "depth" / "000001.png");
                     png[60] = static_cast<char>(png[60] ^ 0xFF);
                     writeText(rec / "depth" / "000001.png", png);
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"000001.png", "corrupt"},
                 {"rec"}});
    c.push_back({"CorruptGltfInTheScene",
                 [](const fs::path& d) {
                     const fs::path scene = writeScene(d);
                     writeText(d / "ground.gltf",
                               "{\"asset\": {\"version\": \"2.0\"},\n\"meshes\": [");
                     return "render " + str(scene) + " --out " + str(d / "r");
                 },
                 {"ground.gltf"},
                 {"scene.json", "ground.gltf"}});
    c.push_back({"CorruptDensityMap",
                 [](const fs::path& d) {
                     cv::imwrite(str(d / "density.png"), cv::Mat1b(8, 8, std::uint8_t{255}));
                     std::string png = readAll(d / "density.png");
                     png[40] = static_cast<char>(png[40] ^ 0xFF);
                     writeText(d / "density.png", png);
                     return "render " +
                            str(writeScene(d, {{"blades",
                                                {{"density_map",
                                                  {{"image", "density.png"},
                                                   {"min_xz_m", {-0.5, -0.5}},
                                                   {"max_xz_m", {0.5, 0.5}}}}}}})) +
                            " --out " + str(d / "r");
                 },
                 {"density.png"},
                 {"scene.json"}});
    // 8. Messages that say what is really wrong.
    c.push_back({"SourceThatIsALoopOfSymbolicLinks",
                 [](const fs::path& d) {
                     fs::create_symlink(d / "b", d / "a");
                     fs::create_symlink(d / "a", d / "b");
                     return "capture " + str(d / "a") + " --out " + str(d / "l.json");
                 },
                 {"loop of symbolic links"},
                 {}});
    c.push_back({"FrameThatIsAFolder",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     fs::remove(rec / "depth" / "000001.png");
                     fs::create_directory(rec / "depth" / "000001.png");
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"000001.png", "is a folder"},
                 {"rec"}});
    c.push_back({"SceneThatIsAFolder",
                 [](const fs::path& d) {
                     fs::create_directory(d / "scene.json");
                     return "render " + str(d / "scene.json") + " --out " + str(d / "r");
                 },
                 {"scene.json", "folder"},
                 {}});
    c.push_back({"LibraryThatIsALoopOfSymbolicLinks",
                 [](const fs::path& d) {
                     fs::create_symlink(d / "l2.json", d / "l1.json");
                     fs::create_symlink(d / "l1.json", d / "l2.json");
                     return "render " + str(writeScene(d)) + " --library " + str(d / "l1.json") +
                            " --out " + str(d / "r");
                 },
                 {"l1.json", "loop of symbolic links"},
                 {"scene.json"}});
    // Files of every format, truncated, empty, of another format or version.
    c.push_back({"RecordingJsonTruncated",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     const std::string text = readAll(rec / "recording.json");
                     writeText(rec / "recording.json", text.substr(0, text.size() / 2));
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"recording.json", "not valid JSON"},
                 {"rec"}});
    c.push_back({"RecordingJsonOfAnotherVersion",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     editRecordingJson(rec, "version", 7);
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"recording.json", "version 7"},
                 {"rec"}});
    c.push_back({"FrameTruncated",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     const std::string png = readAll(rec / "depth" / "000001.png");
                     writeText(rec / "depth" / "000001.png", png.substr(0, png.size() / 2));
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"000001.png", "truncated"},
                 {"rec"}});
    c.push_back({"FrameEmpty",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     writeText(rec / "depth" / "000000.png", "");
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"000000.png", "empty"},
                 {"rec"}});
    c.push_back({"OniThatIsNoOni",
                 [](const fs::path& d) {
                     writeText(d / "x.oni", "these are not depth frames");
                     return "capture " + str(d / "x.oni") + " --out " + str(d / "l.json");
                 },
                 {"x.oni"},
                 {"x.oni"}});
    c.push_back({"OniTruncated",
                 [](const fs::path& d) {
                     writeText(d / "x.oni", std::string("NI10", 4) + std::string(20, '\1'));
                     return "convert " + str(d / "x.oni") + " " + str(d / "rec");
                 },
                 {"x.oni"},
                 {"x.oni"}});
    c.push_back({"LibraryEmpty",
                 [](const fs::path& d) {
                     writeText(d / "lib.json", "");
                     return "render " + str(writeScene(d)) + " --library " + str(d / "lib.json") +
                            " --out " + str(d / "r");
                 },
                 {"lib.json"},
                 {"lib.json"}});
    c.push_back({"LibraryOfAnotherFormat",
                 [](const fs::path& d) {
                     writeText(d / "lib.json", R"({"format": "meadow.scene", "version": 1})");
                     return "render " + str(writeScene(d)) + " --library " + str(d / "lib.json") +
                            " --out " + str(d / "r");
                 },
                 {"lib.json", "meadow.archetype-library"},
                 {"lib.json"}});
    c.push_back({"LibraryOfAnotherVersion",
                 [](const fs::path& d) {
                     std::string text = readAll(writeLibrary(d / "lib.json"));
                     text.replace(text.find("\"version\": 1"), 12, "\"version\": 9");
                     writeText(d / "lib.json", text);
                     return "render " + str(writeScene(d)) + " --library " + str(d / "lib.json") +
                            " --out " + str(d / "r");
                 },
                 {"lib.json", "version 9"},
                 {"lib.json"}});
    c.push_back({"LibraryMissing",
                 [](const fs::path& d) {
                     return "render " + str(writeScene(d)) + " --library " +
                            str(d / "nowhere.json") + " --out " + str(d / "r");
                 },
                 {"nowhere.json", "does not exist"},
                 {"scene.json"}});
    c.push_back({"SceneEmpty",
                 [](const fs::path& d) {
                     writeText(d / "scene.json", "");
                     return "render " + str(d / "scene.json") + " --out " + str(d / "r");
                 },
                 {"scene.json", "not valid JSON"},
                 {"scene.json"}});
    c.push_back(
        {"SceneOfAnotherVersion",
         [](const fs::path& d) {
             return "render " + str(writeScene(d, {{"version", 3}})) + " --out " + str(d / "r");
         },
         {"scene.json", "version 3"},
         {"scene.json"}});
    c.push_back({"SceneMeshMissing",
                 [](const fs::path& d) {
                     const fs::path scene = writeScene(d);
                     fs::remove(d / "ground.gltf");
                     return "render " + str(scene) + " --out " + str(d / "r");
                 },
                 {"ground.gltf"},
                 {"scene.json"}});
    c.push_back({"SceneMeshWithNoTriangles",
                 [](const fs::path& d) {
                     const fs::path scene = writeScene(d);
                     writeText(d / "ground.gltf", R"({"asset": {"version": "2.0"}})");
                     return "render " + str(scene) + " --out " + str(d / "r");
                 },
                 {"ground.gltf", "no triangles"},
                 {"scene.json"}});
    c.push_back(
        {"SceneGlbThatIsText",
         [](const fs::path& d) {
             runtime::test::writeQuad(d / "ground.gltf", -0.5f, 0.5f, -0.5f, 0.5f);
             writeText(d / "ground.glb", "not a binary glTF");
             return "render " +
                    str(runtime::test::writeScene(d, runtime::test::minimalScene("ground.glb"))) +
                    " --out " + str(d / "r");
         },
         {"ground.glb"},
         {"scene.json"}});
    c.push_back({"TruthOfAnotherFormatIsNotReadAsARecording",
                 [](const fs::path& d) {
                     const fs::path rec = writeNoiseRecording(d / "rec");
                     writeText(rec / "recording.json",
                               R"({"format": "meadow.synth-truth", "version": 1})");
                     return "capture " + str(rec) + " --out " + str(d / "l.json");
                 },
                 {"recording.json", "not a meadow recording"},
                 {"rec"}});
    c.push_back({"PlainFolderWithoutIntrinsics",
                 [](const fs::path& d) {
                     fs::create_directories(d / "png");
                     cv::imwrite(str(d / "png" / "0.png"), cv::Mat1w(48, 64, std::uint16_t{900}));
                     return "capture " + str(d / "png") + " --out " + str(d / "l.json");
                 },
                 {"--intrinsics", "--depth-unit"},
                 {"png"}});
    c.push_back({"PlainFolderOfColourImages",
                 [](const fs::path& d) {
                     fs::create_directories(d / "png");
                     cv::imwrite(str(d / "png" / "0.png"), cv::Mat3b(48, 64, cv::Vec3b(1, 2, 3)));
                     return "capture " + str(d / "png") + " --out " + str(d / "l.json") +
                            " --intrinsics 58,58,31.5,23.5 --depth-unit mm";
                 },
                 {"0.png", "16-bit"},
                 {"png"}});
    // Options outside what they can mean.
    c.push_back({"RenderSizeOfNoImage",
                 [](const fs::path& d) {
                     return "render " + str(writeScene(d)) + " --out " + str(d / "r") +
                            " --size 0x99999";
                 },
                 {"--size"},
                 {"scene.json"}});
    c.push_back({"CaptureBandUpsideDown",
                 [](const fs::path& d) {
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "l.json") + " --near 2 --far 1";
                 },
                 {"--near/--far"},
                 {"rec"}});
    c.push_back({"CaptureOneKnot",
                 [](const fs::path& d) {
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "l.json") + " --knots 1";
                 },
                 {"--knots"},
                 {"rec"}});
    c.push_back({"CaptureUnknownFusion",
                 [](const fs::path& d) {
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "l.json") + " --fusion mean";
                 },
                 {"--fusion"},
                 {"rec"}});
    c.push_back({"CaptureUnknownPlaneMethod",
                 [](const fs::path& d) {
                     return "capture " + str(writeNoiseRecording(d / "rec")) + " --out " +
                            str(d / "l.json") + " --plane organized";
                 },
                 {"--plane"},
                 {"rec"}});
    c.push_back({"SynthFramesBeyondItsLimit",
                 [](const fs::path& d) {
                     return "synth --preset thin --frames 10001 --out " + str(d / "rec");
                 },
                 {"--frames"},
                 {}});
    c.push_back({"SynthUnknownPreset",
                 [](const fs::path& d) { return "synth --preset lawn --out " + str(d / "rec"); },
                 {"lawn", "slim-grass"},
                 {}});
    c.push_back({"ConvertWithoutAnOniSide",
                 [](const fs::path& d) {
                     return "convert " + str(writeNoiseRecording(d / "rec")) + " " +
                            str(d / "copy");
                 },
                 {".oni"},
                 {"rec"}});
    return c;
}

void PrintTo(const BadInput& bad, std::ostream* out) { *out << bad.name; }

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, IsOneLineExitingTwoNamingTheCulpritAndKeepsEveryEarlierOutput) {
    const BadInput& bad = GetParam();
    const fs::path dir = freshTempDir("bad_input_" + bad.name);
    const std::string args = bad.setup(dir);
    std::map<std::string, std::string> before;
    for (const std::string& kept : bad.keep) before.merge(snapshot(dir / kept));

    const CommandResult r = runMeadow(args);
    EXPECT_EQ(r.exitCode, 2) << args << "\n" << r.output;
    EXPECT_EQ(countLines(r.output), 1) << args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("meadow: ", 0), 0u) << r.output;
    for (const std::string& m : bad.mentions)
        EXPECT_NE(r.output.find(m), std::string::npos) << "should mention " << m << ":\n"
                                                       << r.output;
    std::map<std::string, std::string> after;
    for (const std::string& kept : bad.keep) after.merge(snapshot(dir / kept));
    EXPECT_EQ(before.size(), after.size()) << "files kept";
    for (const auto& [file, bytes] : before)
        EXPECT_TRUE(after.contains(file) && after.at(file) == bytes) << file << " changed";
    EXPECT_FALSE(anyTemporary(dir)) << "a temporary was left in " << dir;
}

INSTANTIATE_TEST_SUITE_P(Every, BadInputTest, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<BadInput>& info) {
                             return info.param.name;
                         });

}  // namespace
}  // namespace meadow::test
