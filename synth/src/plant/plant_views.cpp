#include "meadow/synth/plant_views.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <opencv2/core.hpp>

#include "meadow/synth/error.h"
#include "meadow/synth/synthesize.h"
#include "meadow/synth/synthetic_tuft.h"
#include "plant_scenery.h"
#include "point_splats.h"

namespace meadow::synth {
namespace {

// A scanned point is seen when the surface at its pixel lies no more than this in front of it
// (its own splat, drawn a little in front where the leaf curves).
constexpr float kVisibleTolerance_m = 0.01f;
// With no distance given, the camera stands where the plant's height fills this share of the
// image's, and no nearer than a depth camera reads well.
constexpr float kAutoFill = 0.7f;
constexpr float kMinAutoDistance_m = 0.8f;

void checkOptions(const PlantViewOptions& o) {
    const auto bad = [](const std::string& what) { throw SynthError("plant views: " + what); };
    if (!(o.distance_m == 0.f || (o.distance_m >= 0.2f && o.distance_m <= 10.f)))
        bad("the camera distance must be 0.2-10 m, got " + std::to_string(o.distance_m));
    if (!(o.pitch_deg >= -30.f && o.pitch_deg <= 89.f))
        bad("the pitch must be -30 to 89 degrees, got " + std::to_string(o.pitch_deg));
    if (o.views < 1 || o.views > 360)
        bad("the turntable takes 1-360 views, got " + std::to_string(o.views));
    if (!std::isfinite(o.azimuth_deg) || !std::isfinite(o.aimHeight_m))
        bad("the azimuth and aim height must be finite numbers");
    if (!(o.wallBehind_m >= 0.2f && o.wallBehind_m <= 10.f))
        bad("the wall must stand 0.2-10 m behind the plant, got " + std::to_string(o.wallBehind_m));
}

LabelledMesh transformedMesh(const LabelledMesh& m, const glm::mat4& targetFromSource) {
    LabelledMesh out;
    out.label = m.label;
    out.triangles = m.triangles;
    out.positions_m.reserve(m.positions_m.size());
    for (const glm::vec3& p : m.positions_m)
        out.positions_m.push_back(glm::vec3(targetFromSource * glm::vec4(p, 1.f)));
    return out;
}

}  // namespace

PlantViewOptions resolvedPlantViewOptions(const ScannedPlant& plant,
                                          const PlantViewOptions& options,
                                          const capture::Intrinsics& k) {
    PlantViewOptions o = options;
    const float height = plant.height_m();
    if (!(o.aimHeight_m >= 0.f)) o.aimHeight_m = 0.5f * height;
    if (!(o.distance_m > 0.f))
        o.distance_m = std::max(kMinAutoDistance_m,
                                height * k.fy_px / (kAutoFill * static_cast<float>(k.height_px)));
    return o;
}

std::vector<RenderedPlantView> renderPlantViews(const ScannedPlant& plant,
                                                const PlantViewOptions& options,
                                                const SimulatedSensor& sensor, std::uint64_t seed,
                                                const std::function<void(int, int)>& progress) {
    checkOptions(options);
    // Organs as splat meshes, labelled 1..N in the plant's label order.
    std::vector<LabelledMesh> organs;
    std::vector<std::vector<glm::vec3>> organPoints(plant.organs.size());
    for (std::size_t i = 0; i < plant.points_m.size(); ++i)
        for (std::size_t o = 0; o < plant.organs.size(); ++o)
            if (plant.organs[o].label == plant.labels[i])
                organPoints[o].push_back(plant.points_m[i]);
    for (std::size_t o = 0; o < plant.organs.size(); ++o) {
        const modeling::TriangleMesh splats = plant::splatMesh(organPoints[o]);
        organs.push_back({splats.positions_m, splats.triangles, static_cast<std::uint16_t>(o + 1)});
    }
    const float height = plant.height_m();
    const plant::Scenery scenery =
        options.scenery ? plant::benchScenery(height, options.wallBehind_m, options.seed)
                        : plant::Scenery{};

    const capture::Intrinsics& k = sensor.intrinsics();
    TuftCamera camera;
    camera.intrinsics = sensor.intrinsics();
    const PlantViewOptions resolved = resolvedPlantViewOptions(plant, options, k);
    camera.target_m = {0.f, resolved.aimHeight_m, 0.f};
    camera.distance_m = resolved.distance_m;
    camera.tilt_rad = glm::radians(options.pitch_deg);
    const glm::mat4 cameraFromWorld = camera.cameraFromWorld();

    std::vector<RenderedPlantView> out;
    for (int v = 0; v < options.views; ++v) {
        const float azimuth = options.azimuth_deg + 360.f * static_cast<float>(v) / options.views;
        const glm::mat4 turned =
            glm::rotate(glm::mat4(1.f), glm::radians(azimuth), {0.f, 1.f, 0.f});
        const glm::mat4 cameraFromPlant = cameraFromWorld * turned;
        std::vector<LabelledMesh> meshes;
        for (const LabelledMesh& m : scenery.meshes)
            meshes.push_back(transformedMesh(m, cameraFromWorld));
        for (const LabelledMesh& m : organs) meshes.push_back(transformedMesh(m, cameraFromPlant));
        RenderedPlantView view;
        view.frame = sensor.render(meshes, synthFrameSeed(seed, static_cast<std::uint64_t>(v)));
        PlantTruthView& t = view.truth;
        t.index = v;
        t.azimuth_deg = azimuth;
        t.cameraFromWorld = cameraFromPlant;
        const cv::Mat1w& labels = view.frame.labels;
        for (std::size_t o = 0; o < plant.organs.size(); ++o) {
            const PlantOrgan& organ = plant.organs[o];
            PlantTruthOrgan to;
            to.id = static_cast<int>(o + 1);
            to.sourceLabel = organ.label;
            to.stem = organ.stem;
            for (const glm::vec3& p : organ.centreLine_m)
                to.centreLineCamera_m.push_back(glm::vec3(cameraFromPlant * glm::vec4(p, 1.f)));
            to.length_m = organ.length_m;
            to.maxWidth_m = organ.maxWidth_m;
            to.visiblePixels = cv::countNonZero(labels == to.id);
            int seen = 0;
            for (const glm::vec3& p : organPoints[o]) {
                const glm::vec3 c(cameraFromPlant * glm::vec4(p, 1.f));
                if (!(c.z > 0.f)) continue;
                const glm::vec2 px = k.project(c);
                const int u = static_cast<int>(std::lround(px.x)),
                          w = static_cast<int>(std::lround(px.y));
                if (u < 0 || w < 0 || u >= labels.cols || w >= labels.rows) continue;
                seen +=
                    labels(w, u) == to.id && view.frame.exact_m(w, u) >= c.z - kVisibleTolerance_m;
            }
            to.visibleShare =
                organPoints[o].empty()
                    ? 0.f
                    : static_cast<float>(seen) / static_cast<float>(organPoints[o].size());
            t.organs.push_back(std::move(to));
        }
        out.push_back(std::move(view));
        if (progress) progress(v + 1, options.views);
    }
    return out;
}

}  // namespace meadow::synth
