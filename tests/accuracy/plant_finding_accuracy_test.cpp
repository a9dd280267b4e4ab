// Finding the plant in a scene (SegmenterParams::plantFinding = Clusters): scanned plants in a
// pot on a floor before a wall with clutter, rendered through the calibrated Kinect v1 model,
// must come out with their leaves and without the room; a room without a plant must say so.
#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "meadow/capture/segmenter.h"
#include "meadow/synth/plant_views.h"
#include "meadow/synth/scanned_plant.h"
#include "meadow/synth/sensor_figures.h"
#include "meadow/synth/sensor_models.h"
#include "support/shared_data.h"

namespace meadow::synth {
namespace {

struct Found {
    double plantShare = 0.0;  // of the plant's pixels (stem and leaves), in the mask
    double roomShare = 0.0;   // of the mask, on the floor, wall, pot or clutter
    int views = 0, withPlant = 0;
};

capture::SegmenterParams findingBy(capture::PlantFinding finding) {
    capture::SegmenterParams params;
    params.plantFinding = finding;
    return params;
}

Found findInViews(
    const ScannedPlant& plant, int views,
    const capture::SegmenterParams& params = findingBy(capture::PlantFinding::Clusters),
    SensorKind kind = SensorKind::KinectV1) {
    const SensorModel model = sensorModel(kind);
    const SimulatedSensor sensor(model.intrinsics, model.noise);
    PlantViewOptions options;
    options.views = views;
    const capture::Segmenter segmenter(params);
    Found f;
    long plantPixels = 0, plantFound = 0, maskPixels = 0, roomInMask = 0;
    for (const RenderedPlantView& view : renderPlantViews(plant, options, sensor, 1)) {
        capture::DepthFrame frame;
        frame.depth_mm = view.frame.depth_mm;
        frame.intrinsics = model.intrinsics;
        const capture::Segmentation seg = segmenter.segment(frame);
        ++f.views;
        f.withPlant += !seg.noPlant;
        if (seg.clusterMask.empty()) continue;
        for (int y = 0; y < frame.depth_mm.rows; ++y)
            for (int x = 0; x < frame.depth_mm.cols; ++x) {
                const std::uint16_t label = view.frame.labels(y, x);
                const bool isPlant = label > 0 && label < kFloorLabel;
                const bool read = frame.depth_mm(y, x) > 0;
                const bool inMask = seg.clusterMask(y, x) != 0;
                plantPixels += isPlant && read;
                plantFound += isPlant && read && inMask;
                maskPixels += inMask;
                roomInMask += inMask && label >= kFloorLabel;
            }
    }
    f.plantShare = plantPixels ? static_cast<double>(plantFound) / plantPixels : 0.0;
    f.roomShare = maskPixels ? static_cast<double>(roomInMask) / maskPixels : 0.0;
    return f;
}

// A grown maize shoot (Label3DMaize v-9-1) from four sides: found in every view with most of
// its pixels, little of the room along. (A young shoot's pot, which the floor's removal leaves
// too low to tell by its thickness, is not yet taken off: docs/capture.md#finding-the-plant.)
TEST(PlantFinding, AGrownMaizeShootIsFoundAndTheRoomLeftOut) {
    const auto scans = test::sharedDataDir() / "real" / "maize-label3d";
    if (!std::filesystem::exists(scans)) GTEST_SKIP() << "shared data not present: " << scans;
    const ScannedPlant plant = loadScannedPlant(scans / "v-9-1-l-r.txt");
    const Found f = findInViews(plant, 4);
    EXPECT_EQ(f.withPlant, f.views);
    EXPECT_GE(f.plantShare, 0.8);
    EXPECT_LE(f.roomShare, 0.1);
}

// The grown shoot of v-12-1 (leaves 7-13 cm across) seen 2 m away by a stereo camera, which
// fattens its edges: its parts measure 4.2-5.6 cm, wider than a grass's, but they are long, and
// it is found in every view. Its mask holds 22 % of the room's pixels: most (16 % of the mask)
// are the wall's beside the leaves that the camera reads at the leaves' depth, its fattened edges.
TEST(PlantFinding, ABroadLeavedShootFarFromAStereoCameraIsFound) {
    const auto scans = test::sharedDataDir() / "real" / "maize-label3d";
    if (!std::filesystem::exists(scans)) GTEST_SKIP() << "shared data not present: " << scans;
    const ScannedPlant plant = loadScannedPlant(scans / "v-12-1-l-r.txt");
    const Found f = findInViews(plant, 4, findingBy(capture::PlantFinding::Clusters),
                                SensorKind::RealSenseD435);
    EXPECT_EQ(f.withPlant, f.views);
    EXPECT_GE(f.plantShare, 0.6);
    EXPECT_LE(f.roomShare, 0.25);
}

// The default depth band takes the nearest depth mode, here a leaf's or the plant's: it must not
// take the plant for furniture.
TEST(PlantFinding, AGrownMaizeShootIsNotTakenForFurnitureByTheDepthBand) {
    const auto scans = test::sharedDataDir() / "real" / "maize-label3d";
    if (!std::filesystem::exists(scans)) GTEST_SKIP() << "shared data not present: " << scans;
    const ScannedPlant plant = loadScannedPlant(scans / "v-9-1-l-r.txt");
    const Found f = findInViews(plant, 4, findingBy(capture::PlantFinding::DepthMode));
    EXPECT_EQ(f.withPlant, f.views);
}

// A room of planes and furniture-like boxes and no plant: no plant, and no mask, whichever way
// the plant is looked for.
class RoomWithoutAPlant : public ::testing::TestWithParam<capture::PlantFinding> {};

TEST_P(RoomWithoutAPlant, HasNone) {
    const SensorModel model = sensorModel(SensorKind::KinectV1);
    const SimulatedSensor sensor(model.intrinsics, model.noise);
    capture::SegmenterParams params;
    params.plantFinding = GetParam();
    capture::DepthFrame frame;
    frame.depth_mm = sensor.render(calibrationRoom(), 1).depth_mm;
    frame.intrinsics = model.intrinsics;
    const capture::Segmentation seg = capture::Segmenter(params).segment(frame);
    EXPECT_TRUE(seg.noPlant) << seg.summary();
    EXPECT_TRUE(seg.blades.empty());
    EXPECT_NE(seg.noBladesReason.find("no plant"), std::string::npos) << seg.noBladesReason;
}

INSTANTIATE_TEST_SUITE_P(PlantFinding, RoomWithoutAPlant,
                         ::testing::Values(capture::PlantFinding::DepthMode,
                                           capture::PlantFinding::Clusters),
                         [](const auto& info) {
                             return info.param == capture::PlantFinding::Clusters
                                        ? std::string("Clusters")
                                        : std::string("DepthMode");
                         });

}  // namespace
}  // namespace meadow::synth
