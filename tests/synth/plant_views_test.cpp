// A scanned plant as the simulated sensor sees it (plant_views.h): splats close a sparse scan
// into a surface without holes, and the rendered depth and labels agree with the scanned points
// (noise off): the depth within the sensor's own sigma, the label the point's organ.
#include "meadow/synth/plant_views.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "meadow/synth/sensor_models.h"
#include "plant/point_splats.h"
#include "support/made_plant.h"
#include "support/shared_data.h"
#include "support/test_util.h"

namespace meadow::synth {
namespace {

// A square of random points 1 m before a Kinect v1, turned by `turn_rad` about the vertical.
TEST(PlantViews, AFlatSquareOfRandomPointsRendersWithoutHolesAtItsDepth) {
    for (float turn : {0.f, 0.7f}) {
        std::mt19937 rng(3);
        std::uniform_real_distribution<float> side(-0.15f, 0.15f);
        std::vector<glm::vec3> points;
        for (int i = 0; i < 5000; ++i) {  // 4 mm apart on average, sparser than the 1.7 mm pixels
            const float x = side(rng), y = side(rng);
            points.push_back({x * std::cos(turn), y, 1.f + x * std::sin(turn)});
        }
        const modeling::TriangleMesh splats = plant::splatMesh(points);
        const SimulatedSensor sensor(capture::Intrinsics::kinectV1(), NoiseModel::none());
        const SimulatedFrame frame = sensor.render({{splats.positions_m, splats.triangles, 1}}, 1);
        const capture::Intrinsics k = capture::Intrinsics::kinectV1();
        int inside = 0, holes = 0;
        double worst_mm = 0.0;
        for (int v = 0; v < frame.depth_mm.rows; ++v)
            for (int u = 0; u < frame.depth_mm.cols; ++u) {
                // Where the pixel's ray meets the square's plane, 1 cm in from its edges.
                const glm::vec3 ray =
                    k.backProject(static_cast<float>(u), static_cast<float>(v), 1.f);
                const glm::vec3 n(-std::sin(turn), 0.f, std::cos(turn));
                const float t = glm::dot(glm::vec3(0.f, 0.f, 1.f), n) / glm::dot(ray, n);
                const glm::vec3 hit = t * ray;
                const float x = glm::dot(hit - glm::vec3(0.f, 0.f, 1.f),
                                         glm::vec3(std::cos(turn), 0.f, std::sin(turn)));
                if (std::abs(x) > 0.14f || std::abs(hit.y) > 0.14f) continue;
                ++inside;
                if (frame.depth_mm(v, u) == 0) {
                    ++holes;
                    continue;
                }
                worst_mm = std::max(worst_mm, std::abs(frame.depth_mm(v, u) - 1000.0 * hit.z));
            }
        EXPECT_GT(inside, 20000);
        EXPECT_EQ(holes, 0) << "turned " << turn << " rad";
        EXPECT_LE(worst_mm, 1.0) << "turned " << turn << " rad";
    }
}

// Scanned points seen in a view, in camera space, with their organ id.
struct SeenPoint {
    glm::vec3 camera_m;
    int id;
};

class RealPlantViews : public ::testing::TestWithParam<SensorKind> {};

TEST_P(RealPlantViews, ARealMaizeShootsDepthAndLabelsMatchItsScannedPoints) {
    const std::filesystem::path file =
        test::sharedDataDir() / "real" / "maize-label3d" / "v-9-1-l-r.txt";
    if (!std::filesystem::exists(file)) GTEST_SKIP() << "shared data not present: " << file;
    const ScannedPlant plant = loadScannedPlant(file);
    const SensorModel model = sensorModel(GetParam());
    const SimulatedSensor sensor(model.intrinsics, NoiseModel::none());
    PlantViewOptions options;
    options.views = 2;
    options.distance_m = 1.f;
    const std::vector<RenderedPlantView> views = renderPlantViews(plant, options, sensor, 1);
    ASSERT_EQ(views.size(), 2u);
    const capture::Intrinsics& k = sensor.intrinsics();
    for (const RenderedPlantView& view : views) {
        std::vector<float> depthError_m;
        int near = 0, labelled = 0;
        for (std::size_t i = 0; i < plant.points_m.size(); ++i) {
            int id = 0;
            for (std::size_t o = 0; o < plant.organs.size(); ++o)
                if (plant.organs[o].label == plant.labels[i]) id = static_cast<int>(o + 1);
            const glm::vec3 c(view.truth.cameraFromWorld * glm::vec4(plant.points_m[i], 1.f));
            const glm::vec2 px = k.project(c);
            const int u = static_cast<int>(std::lround(px.x)),
                      v = static_cast<int>(std::lround(px.y));
            if (u < 0 || v < 0 || u >= k.width_px || v >= k.height_px) continue;
            const float exact = view.frame.exact_m(v, u);
            if (!(exact > 0.f) || exact < c.z - 0.005f) continue;  // something lies in front
            depthError_m.push_back(std::abs(exact - c.z));
            if (exact < c.z + 0.005f) {
                ++near;
                labelled += view.frame.labels(v, u) == id;
            }
        }
        ASSERT_GT(depthError_m.size(), 2000u);
        std::nth_element(
            depthError_m.begin(),
            depthError_m.begin() + static_cast<std::ptrdiff_t>(depthError_m.size() / 2),
            depthError_m.end());
        const float median = depthError_m[depthError_m.size() / 2];
        // Under the sensor's own sigma at the plant's distance: the axial noise and, for a
        // sensor that quantises disparity, a uniform step's sigma (step / sqrt(12)). The splats
        // themselves lie about a millimetre off their points (the scan's own scatter: each
        // point is covered by the splats of its neighbours, the nearest of which is seen).
        const float axial_m = model.noise.axialSigma_m(options.distance_m, 0.f);
        const float step_m = model.noise.quantisation
                                 ? disparityStep_m(options.distance_m, model.intrinsics.fx_px,
                                                   model.noise.baseline_m, model.noise.subpixel)
                                 : 0.f;
        EXPECT_LT(median, std::sqrt(axial_m * axial_m + step_m * step_m / 12.f))
            << "view " << view.truth.index;
        EXPECT_GE(labelled, 0.95 * near) << "view " << view.truth.index;
        // Every organ's truth is there, and the leaves the camera sees show.
        int shown = 0;
        for (const PlantTruthOrgan& o : view.truth.organs) shown += o.visiblePixels > 0;
        EXPECT_GE(shown, 8) << "of 10 organs in view " << view.truth.index;
    }
}

INSTANTIATE_TEST_SUITE_P(EverySensor, RealPlantViews,
                         ::testing::Values(SensorKind::KinectV1, SensorKind::KinectV2,
                                           SensorKind::RealSenseD435),
                         [](const ::testing::TestParamInfo<SensorKind>& info) {
                             std::string name(kSensorKindNames.name(info.param));
                             std::erase(name, '-');
                             return name;
                         });

}  // namespace
}  // namespace meadow::synth
