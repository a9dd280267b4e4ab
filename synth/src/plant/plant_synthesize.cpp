// The `meadow synth --plant` driver: scanned plant -> bench views through the simulated sensor ->
// recording + truth.
#include "meadow/synth/plant_synthesize.h"

#include <optional>

#include "meadow/capture/recording.h"
#include "meadow/core/atomic_file.h"
#include "meadow/core/staged_folder.h"
#include "meadow/synth/error.h"
#include "meadow/synth/sensor_models.h"
#include "meadow/synth/simulated_sensor.h"
#include "meadow/synth/synthesize.h"
#include "truth_folder.h"

namespace meadow::synth {
namespace {

constexpr const char* kPlantTruthFileName = "plant.json";
constexpr float kMaxNoiseScale = 10.f;

SensorModel sensorNamed(const std::string& name, float noiseScale) {
    const std::optional<SensorKind> kind = kSensorKindNames.parse(name);
    if (!kind)
        throw SynthError("unknown sensor '" + name +
                         "'; known sensors: " + kSensorKindNames.list());
    SensorModel s = sensorModel(*kind);
    s.noise.scale = noiseScale;
    return s;
}

}  // namespace

std::vector<std::string> plantSensorNames() { return kSensorKindNames.names(); }

PlantTruth synthesizePlant(const PlantSynthOptions& options,
                           const std::function<void(int, int)>& progress) {
    if (!(options.noiseScale >= 0.f && options.noiseScale <= kMaxNoiseScale))
        throw SynthError("the noise scale must be in [0, 10], got " +
                         std::to_string(options.noiseScale));
    const SensorModel sensor = sensorNamed(options.sensor, options.noiseScale);
    const ScannedPlant plant = loadScannedPlant(options.plant, options.scan);
    detail::checkReplaceableSynthOutput(options.out);
    const SimulatedSensor simulated(sensor.intrinsics, sensor.noise);
    std::vector<RenderedPlantView> views =
        renderPlantViews(plant, options.views, simulated, options.seed, progress);

    PlantTruth truth;
    truth.plant = plant.name;
    truth.source = options.plant.string();
    truth.unit = std::string(kLengthUnitNames.name(options.scan.unit));
    truth.stemFoundBy = plant.stemFoundBy;
    truth.sensor = sensor.description;
    truth.noiseScale = options.noiseScale;
    truth.intrinsics = sensor.intrinsics;
    truth.options = resolvedPlantViewOptions(plant, options.views, sensor.intrinsics);

    StagedFolder staged(options.out);
    capture::RecordingInfo info;
    info.sensor = "meadow synth (" + sensor.description + ", plant " + plant.name + ", " +
                  std::to_string(options.views.views) + " turntable view(s))";
    info.intrinsics = sensor.intrinsics;
    info.frameRate_hz = kSynthFrameRate_hz;
    capture::RecordingWriter writer(staged.path(), info);
    const std::filesystem::path truthFolder = staged.path() / detail::kTruthFolderName;
    for (RenderedPlantView& v : views) {
        writer.write(v.frame.depth_mm);
        v.truth.labels = detail::labelsPath(v.truth.index);
        detail::writeLabels(truthFolder / v.truth.labels, v.frame.labels);
        truth.views.push_back(std::move(v.truth));
    }
    writeFileAtomically(truthFolder / kPlantTruthFileName, plantTruthToJson(truth));
    writer.finish();
    staged.commit();
    return truth;
}

}  // namespace meadow::synth
