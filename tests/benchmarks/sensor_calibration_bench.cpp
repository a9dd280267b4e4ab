// The simulated sensors against a real one: the figures of synth/sensor_figures.h (temporal sigma
// per depth, share of mixed pixels at depth steps, how far edge displacement runs along an edge)
// measured on the real Kinect recording ../shared/data/real/oni-3dj-room and, the same way, on
// each simulated sensor filming a room laid out like it (calibrationRoom), 12 frames each. The
// Kinect v1 rows say how far each figure lies from the real one. Writes sensor_calibration.md and
// .csv into --out. Run by tools/measure.sh.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "common/report.h"
#include "meadow/capture/depth_source.h"
#include "meadow/synth/sensor_figures.h"
#include "meadow/synth/sensor_models.h"

namespace meadow::bench {
namespace {

namespace fs = std::filesystem;

// The bounds for the Kinect v1 model: sigma within 15 %, edge figures within x1.5.
constexpr double kSigmaTolerance = 0.15;
constexpr double kEdgeFactor = 1.5;
constexpr int kFrames = 12;  // as many as the real recording holds

struct Row {
    std::string source;  // "real Kinect v1 recording" or a sensor model's name
    synth::SensorFigures figures;
};

std::vector<cv::Mat1w> realFrames(const fs::path& oni) {
    auto source = capture::openDepthSource(oni.string());
    std::vector<cv::Mat1w> frames;
    while (auto frame = source->next()) frames.push_back(frame->depth_mm.clone());
    return frames;
}

double sigmaIn(const synth::SensorFigures& f, float from_m) {
    for (const synth::DepthBinSigma& b : f.temporalSigma)
        if (std::abs(b.from_m - from_m) < 1e-3f) return b.sigma_mm;
    return std::nan("");
}

std::string ratioCell(double simulated, double real) {
    if (!(real > 0.0) || !std::isfinite(simulated)) return "-";
    return fixed(simulated / real, 2);
}

int run(int argc, char** argv) {
    fs::path out = fs::path(MEADOW_SOURCE_DIR) / "docs/measurements";
    fs::path data = fs::path(MEADOW_SOURCE_DIR) / "../shared/data/real";
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--out" && i + 1 < argc)
            out = argv[++i];
        else if (arg == "--data" && i + 1 < argc)
            data = argv[++i];
        else if (arg == "--made" && i + 1 < argc)
            setMadeLine(argv[++i]);
        else if (arg == "--quick")
            ;  // twelve frames of one room are already quick
        else {
            std::cerr << "usage: meadow_sensor_calibration_bench [--out DIR] [--data DIR] "
                         "[--made TEXT]\n";
            return 2;
        }
    }
    fs::create_directories(out);
    const fs::path oni = data / "oni-3dj-room" / "test.oni";
    std::vector<Row> rows;
    std::optional<synth::SensorFigures> real;
    if (fs::exists(oni)) {
        real = synth::measureSensorFigures(realFrames(oni));
        rows.push_back({"real Kinect v1 recording (oni-3dj-room)", *real});
    } else {
        std::cout << "sensor calibration: " << oni << " absent; simulated rows only\n";
    }
    const auto room = synth::calibrationRoom();
    const auto simulate = [&](const std::string& name, const synth::SensorModel& model) {
        const synth::SimulatedSensor sensor(model.intrinsics, model.noise);
        rows.push_back({name, synth::measureSensorFigures(
                                  synth::renderStillFrames(sensor, room, kFrames, 1))});
        std::cout << "sensor calibration: " << name << " measured\n";
    };
    simulate(synth::kUncalibratedKinectV1Name, synth::uncalibratedKinectV1());
    for (const synth::SensorKind kind : {synth::SensorKind::KinectV1, synth::SensorKind::KinectV2,
                                         synth::SensorKind::RealSenseD435})
        simulate(std::string(synth::kSensorKindNames.name(kind)), synth::sensorModel(kind));

    // Depth bins any row measured.
    std::vector<float> bins;
    for (const Row& r : rows)
        for (const synth::DepthBinSigma& b : r.figures.temporalSigma)
            if (std::find(bins.begin(), bins.end(), b.from_m) == bins.end())
                bins.push_back(b.from_m);
    std::sort(bins.begin(), bins.end());
    const float binWidth_m = synth::FigureOptions{}.binWidth_m;

    std::ostringstream md, csv;
    md << "# Simulated sensors against a real Kinect recording\n\n"
          "The real Kinect v1 recording `../shared/data/real/oni-3dj-room` (12 frames of a still "
          "room) and each simulated sensor filming a room laid out like it, measured the same "
          "way (synth/sensor_figures.h; docs/capture.md, \"Sensor models\"): temporal sigma of "
          "each pixel over the frames, by depth; the share of readings within 2 px of a depth "
          "step over 50 mm that lie off both sides (mixed, or flying, pixels); the mean length "
          "of the runs along an edge over which its displacement keeps its sign. In brackets: "
          "the simulated figure over the real one, for the Kinect v1 models, whose bounds are "
          "sigma within "
       << fixed(100 * kSigmaTolerance, 0) << " % and edge figures within a factor of "
       << fixed(kEdgeFactor, 1)
       << ". Kinect v2 and RealSense D435 have no real recording here: their rows show what "
          "their published figures give.\n\n| Source |";
    csv << "source";
    for (float b : bins) {
        md << " sigma " << fixed(b, 1) << "-" << fixed(b + binWidth_m, 1) << " m (mm) |";
        csv << ",sigma_" << fixed(b, 1) << "_" << fixed(b + binWidth_m, 1) << "_mm";
    }
    md << " Mixed share at steps | Edge run length (px) | Within bounds |\n|---|";
    csv << ",mixed_share,edge_run_length_px,edge_runs,within_bounds\n";
    for (std::size_t i = 0; i < bins.size() + 3; ++i) md << "---|";
    md << '\n';
    for (const Row& r : rows) {
        const bool v1 = r.source.starts_with("kinect-v1");
        const bool compared = v1 && real.has_value();
        bool within = compared;
        md << "| " << r.source << " |";
        csv << r.source;
        for (float b : bins) {
            const double s = sigmaIn(r.figures, b);
            const double sr = real ? sigmaIn(*real, b) : std::nan("");
            md << ' ' << (std::isfinite(s) ? fixed(s, 1) : "-");
            if (compared && std::isfinite(sr)) {
                md << " (" << ratioCell(s, sr) << ")";
                within = within && std::abs(s / sr - 1.0) <= kSigmaTolerance;
            }
            md << " |";
            csv << ',' << (std::isfinite(s) ? fixed(s, 2) : "");
        }
        const auto edge = [&](double sim, double re) {
            md << ' ' << fixed(sim, 3);
            if (compared) {
                md << " (" << ratioCell(sim, re) << ")";
                within = within && sim > 0.0 && re > 0.0 && sim / re <= kEdgeFactor &&
                         re / sim <= kEdgeFactor;
            }
            md << " |";
        };
        edge(r.figures.mixedShare, real ? real->mixedShare : 0.0);
        edge(r.figures.edgeRunLength_px, real ? real->edgeRunLength_px : 0.0);
        md << ' ' << (compared ? (within ? "yes" : "**no**") : "-") << " |\n";
        csv << ',' << fixed(r.figures.mixedShare, 4) << ',' << fixed(r.figures.edgeRunLength_px, 2)
            << ',' << r.figures.edgeRuns << ',' << (compared ? (within ? "yes" : "no") : "")
            << '\n';
        std::cout << r.source << ": mixed " << r.figures.mixedShare << " runs "
                  << r.figures.edgeRunLength_px << " sigma bins " << r.figures.temporalSigma.size()
                  << '\n';
    }
    writeText(out / "sensor_calibration.md", md.str());
    writeText(out / "sensor_calibration.csv", csv.str());
    return 0;
}

}  // namespace
}  // namespace meadow::bench

int main(int argc, char** argv) {
    try {
        return meadow::bench::run(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "sensor_calibration_bench: " << e.what() << '\n';
        return 1;
    }
}
