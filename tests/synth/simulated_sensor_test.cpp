// The simulated sensor is the ground truth behind every accuracy test, so these tests hold it to
// its own documentation: exact geometry from the rasteriser, and each noise term with the size
// its source gives (Nguyen, Izadi & Lovell 2012; structured-light disparity quantisation).
#include "meadow/synth/simulated_sensor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace {

using meadow::capture::Intrinsics;
using meadow::synth::addQuad;
using meadow::synth::axialSigma_m;
using meadow::synth::boxMesh;
using meadow::synth::disparityStep_m;
using meadow::synth::LabelledMesh;
using meadow::synth::NoiseModel;
using meadow::synth::SimulatedFrame;
using meadow::synth::SimulatedSensor;

constexpr std::uint64_t kSeed = 20121013;
constexpr float kDegree = std::numbers::pi_v<float> / 180.f;
constexpr std::uint16_t kPlaneLabel = 7;

// A rectangle facing the camera at depth z_m spanning [x0, x1] x [y0, y1] (metres).
LabelledMesh frontalRect(float x0, float x1, float y0, float y1, float z_m, std::uint16_t label) {
    LabelledMesh mesh;
    mesh.label = label;
    addQuad(mesh, {x0, y0, z_m}, {x1, y0, z_m}, {x1, y1, z_m}, {x0, y1, z_m});
    return mesh;
}

// A plane through (0, 0, z_m) turned by `angle` about the camera's y axis (0 = facing the
// camera), spanning +-halfWidth_m along its own x and +-halfHeight_m along y.
LabelledMesh turnedPlane(float z_m, float angle_rad, float halfWidth_m, float halfHeight_m,
                         std::uint16_t label) {
    const glm::vec3 along{std::cos(angle_rad), 0.f, std::sin(angle_rad)};
    const glm::vec3 centre{0.f, 0.f, z_m};
    const glm::vec3 up{0.f, halfHeight_m, 0.f};
    LabelledMesh mesh;
    mesh.label = label;
    addQuad(mesh, centre - halfWidth_m * along - up, centre + halfWidth_m * along - up,
            centre + halfWidth_m * along + up, centre - halfWidth_m * along + up);
    return mesh;
}

NoiseModel onlyShadows() {
    NoiseModel m = NoiseModel::none();
    m.shadows = true;
    m.scale = 1.f;
    return m;
}

// Mirrors the sensor's definition of a depth discontinuity between 4-neighbours
// (sensor_noise_edges.h): one side empty, or a jump of more than 3 % of the nearer depth.
bool isJump(float a_m, float b_m) {
    if ((a_m > 0.f) != (b_m > 0.f)) return true;
    return a_m > 0.f && std::abs(a_m - b_m) > 0.03f * std::min(a_m, b_m);
}

// Rendered pixels that border another rendered surface across a depth discontinuity: the
// only pixels allowed to fly.
cv::Mat1b flyingCandidates(const cv::Mat1f& exact_m) {
    cv::Mat1b out = cv::Mat1b::zeros(exact_m.size());
    const int dx[] = {1, -1, 0, 0};
    const int dy[] = {0, 0, 1, -1};
    for (int y = 0; y < exact_m.rows; ++y)
        for (int x = 0; x < exact_m.cols; ++x) {
            if (exact_m(y, x) <= 0.f) continue;
            for (int i = 0; i < 4; ++i) {
                const int nx = x + dx[i], ny = y + dy[i];
                if (nx < 0 || ny < 0 || nx >= exact_m.cols || ny >= exact_m.rows) continue;
                if (exact_m(ny, nx) > 0.f && isJump(exact_m(y, x), exact_m(ny, nx)))
                    out(y, x) = 255;
            }
        }
    return out;
}

std::uint16_t exactMillimetres(float z_m) {
    return static_cast<std::uint16_t>(std::lround(z_m * 1000.f));
}

struct Stats {
    double mean = 0.;
    double stddev = 0.;
    int count = 0;
};

// Error of the reported depth against the exact depth over the pixels of `mask`.
Stats depthError_m(const SimulatedFrame& frame, const cv::Mat1b& mask) {
    double sum = 0., sum2 = 0.;
    int n = 0;
    for (int y = 0; y < mask.rows; ++y)
        for (int x = 0; x < mask.cols; ++x) {
            if (!mask(y, x) || frame.depth_mm(y, x) == 0) continue;
            const double e = frame.depth_mm(y, x) / 1000.0 - frame.exact_m(y, x);
            sum += e;
            sum2 += e * e;
            ++n;
        }
    Stats s;
    s.count = n;
    s.mean = sum / n;
    s.stddev = std::sqrt(sum2 / n - s.mean * s.mean);
    return s;
}

// Pixels of the rendered surface at least margin_px from its silhouette.
cv::Mat1b interior(const cv::Mat1f& exact_m, int margin_px) {
    cv::Mat1b inside = exact_m > 0.f, eroded;
    cv::erode(inside, eroded,
              cv::getStructuringElement(cv::MORPH_RECT, {2 * margin_px + 1, 2 * margin_px + 1}));
    return eroded;
}

// ---------------------------------------------------------------------------------------------
// Axial noise

TEST(SimulatedSensor, AxialSigmaFollowsNguyenEq5) {
    // 0.0012 + 0.0019 (z - 0.4)^2 below 60 deg.
    EXPECT_NEAR(axialSigma_m(1.0f, 0.f), 0.0012 + 0.0019 * 0.36, 1e-7);
    EXPECT_NEAR(axialSigma_m(2.0f, 30.f * kDegree), 0.0012 + 0.0019 * 2.56, 1e-7);
    // Beyond 60 deg: + 0.0001 / sqrt(z) theta^2 / (pi/2 - theta)^2.
    const double theta = 70.0 * std::numbers::pi / 180.0;
    const double grazing = 0.0001 / std::sqrt(1.5) * theta * theta /
                           ((std::numbers::pi / 2 - theta) * (std::numbers::pi / 2 - theta));
    EXPECT_NEAR(axialSigma_m(1.5f, static_cast<float>(theta)), 0.0012 + 0.0019 * 1.21 + grazing,
                1e-6);
    // Finite even at 90 deg, where the paper's term diverges.
    EXPECT_TRUE(std::isfinite(axialSigma_m(1.f, std::numbers::pi_v<float> / 2.f)));
}

// The threshold: measured standard deviation within 10 % of sigma_z (the mm rounding of the
// output adds 1/12 mm^2 of variance, +1.2 % at 1 m, so it fits inside that margin).
TEST(SimulatedSensor, PlaneNoiseStddevMatchesAxialSigmaWithinTenPercentAt1mAnd2m) {
    NoiseModel noise;            // everything nominal ...
    noise.quantisation = false;  // ... except quantisation, whose steps are not Gaussian
    const SimulatedSensor sensor(Intrinsics::kinectV1(), noise);
    for (const float z_m : {1.0f, 2.0f}) {
        // 0.6 z x 0.5 z: well inside the image, with silhouette edges all round.
        const SimulatedFrame frame = sensor.render(
            {frontalRect(-0.3f * z_m, 0.3f * z_m, -0.25f * z_m, 0.25f * z_m, z_m, kPlaneLabel)},
            kSeed);
        const Stats s = depthError_m(frame, interior(frame.exact_m, 10));
        const double sigma_m = axialSigma_m(z_m, 0.f);
        ASSERT_GT(s.count, 50000) << "z " << z_m;
        EXPECT_NEAR(s.stddev, sigma_m, 0.10 * sigma_m) << "z " << z_m << " m, n " << s.count;
        // Unbiased: the mean error is far below sigma (the standard error is ~sigma / 250).
        EXPECT_LT(std::abs(s.mean), 0.05 * sigma_m) << "z " << z_m;
    }
}

// ---------------------------------------------------------------------------------------------
// Quantisation

// Mean size of the steps between distinct depth levels along the rows of a plane turned by
// 45 deg, within +-window_m of z_m, and the mean of the expected steps at those levels.
struct Steps {
    double measured_m = 0.;
    double expected_m = 0.;
    int count = 0;
};
Steps quantisationSteps(float z_m, float window_m) {
    NoiseModel noise = NoiseModel::none();
    noise.quantisation = true;
    const SimulatedSensor sensor(Intrinsics::kinectV1(), noise);
    const SimulatedFrame frame = sensor.render(
        {turnedPlane(z_m, 45.f * kDegree, 0.4f * z_m, 0.2f * z_m, kPlaneLabel)}, kSeed);
    const Intrinsics k = sensor.intrinsics();
    Steps steps;
    double measured = 0., expected = 0.;
    for (int y = 200; y < 280; ++y) {
        // Levels along the row, in order; mm rounding makes single differences 2 or 3 mm at
        // 1 m, but their mean over a run telescopes to the true step.
        std::vector<int> levels;
        for (int x = 0; x < k.width_px; ++x) {
            const int d = frame.depth_mm(y, x);
            if (d == 0 || std::abs(d / 1000.0 - z_m) > window_m) continue;
            if (levels.empty() || levels.back() != d) levels.push_back(d);
        }
        if (levels.size() < 3) continue;
        const int runs = static_cast<int>(levels.size()) - 1;
        measured += std::abs(levels.back() - levels.front()) / 1000.0;
        for (int i = 0; i < runs; ++i)
            expected += disparityStep_m(0.5f * (levels[i] + levels[i + 1]) / 1000.f, k.fx_px,
                                        noise.baseline_m, noise.subpixel);
        steps.count += runs;
    }
    steps.measured_m = measured / steps.count;
    steps.expected_m = expected / steps.count;
    return steps;
}

TEST(SimulatedSensor, QuantisationStepsAreZSquaredOver8FxBWithin15PercentAt1mAnd2m) {
    for (const float z_m : {1.0f, 2.0f}) {
        const Steps s = quantisationSteps(z_m, 0.04f * z_m);
        const double nominal_m = disparityStep_m(z_m, 575.8f, 0.075f, 8.f);
        ASSERT_GT(s.count, 100) << "z " << z_m;
        EXPECT_NEAR(s.measured_m, s.expected_m, 0.15 * s.expected_m) << "z " << z_m;
        EXPECT_NEAR(s.measured_m, nominal_m, 0.15 * nominal_m) << "z " << z_m;
    }
    // The model's own numbers: 2.9 mm at 1 m, 11.6 mm at 2 m.
    EXPECT_NEAR(disparityStep_m(1.f, 575.8f, 0.075f, 8.f), 0.002894, 1e-5);
    EXPECT_NEAR(disparityStep_m(2.f, 575.8f, 0.075f, 8.f), 0.011578, 1e-5);
}

// ---------------------------------------------------------------------------------------------
// Geometry, labels, determinism

TEST(SimulatedSensor, NoneGivesTheExactDepthRoundedToMillimetres) {
    const SimulatedSensor sensor(Intrinsics::kinectV1(), NoiseModel::none());
    const SimulatedFrame frame = sensor.render(
        {turnedPlane(1.2f, 35.f * kDegree, 0.5f, 0.3f, kPlaneLabel),
         boxMesh({-0.1f, -0.1f, 0.3f}, {0.05f, 0.05f, 0.35f}, 3)},  // nearer than 0.4 m
        kSeed);
    int rendered = 0;
    for (int y = 0; y < frame.depth_mm.rows; ++y)
        for (int x = 0; x < frame.depth_mm.cols; ++x) {
            ASSERT_EQ(frame.depth_mm(y, x), exactMillimetres(frame.exact_m(y, x)))
                << "pixel " << x << "," << y << " exact " << frame.exact_m(y, x);
            rendered += frame.exact_m(y, x) > 0.f;
        }
    EXPECT_GT(rendered, 50000);
}

TEST(SimulatedSensor, ExactDepthIsPerspectiveCorrectOnASlantedPlane) {
    const SimulatedSensor sensor(Intrinsics::kinectV1(), NoiseModel::none());
    const float angle_rad = 50.f * kDegree;
    const float z0_m = 1.5f;
    const SimulatedFrame frame =
        sensor.render({turnedPlane(z0_m, angle_rad, 0.6f, 0.4f, kPlaneLabel)}, kSeed);
    // Plane: n . p = n . (0, 0, z0) with n = (-sin a, 0, cos a); the ray through (u, v) is
    // ((u - cx) / fx, (v - cy) / fy, 1) z, so z = z0 cos a / (cos a - sin a (u - cx) / fx).
    const Intrinsics k = sensor.intrinsics();
    int checked = 0;
    for (int y = 0; y < k.height_px; y += 7)
        for (int x = 0; x < k.width_px; x += 5) {
            if (frame.exact_m(y, x) <= 0.f) continue;
            const double rx = (x - k.cx_px) / k.fx_px;
            const double z =
                z0_m * std::cos(angle_rad) / (std::cos(angle_rad) - std::sin(angle_rad) * rx);
            EXPECT_NEAR(frame.exact_m(y, x), z, 1e-5 * z) << "pixel " << x << "," << y;
            EXPECT_NEAR(frame.incidence_rad(y, x),
                        std::acos(std::abs(-std::sin(angle_rad) * rx + std::cos(angle_rad)) /
                                  std::sqrt(rx * rx + std::pow((y - k.cy_px) / k.fy_px, 2) + 1)),
                        1e-4)
                << "pixel " << x << "," << y;
            ++checked;
        }
    EXPECT_GT(checked, 1000);
}

TEST(SimulatedSensor, LabelsAreExactlyTheNearestMeshsLabel) {
    const LabelledMesh nearRect = frontalRect(-0.2f, 0.05f, -0.2f, 0.05f, 0.9f, 11);
    const LabelledMesh farRect = frontalRect(-0.05f, 0.2f, -0.05f, 0.2f, 1.1f, 22);
    const SimulatedSensor sensor(Intrinsics::kinectV1(), NoiseModel::none());
    // Whatever order the meshes come in, the nearer one wins where they overlap.
    for (const auto& meshes : {std::vector{nearRect, farRect}, std::vector{farRect, nearRect}}) {
        const SimulatedFrame frame = sensor.render(meshes, kSeed);
        const Intrinsics k = sensor.intrinsics();
        for (int y = 0; y < k.height_px; ++y)
            for (int x = 0; x < k.width_px; ++x) {
                const glm::vec3 rayAt1m =
                    k.backProject(static_cast<float>(x), static_cast<float>(y), 1.f);
                const auto inside = [&](float x0, float x1, float y0, float y1, float z) {
                    const float px = rayAt1m.x * z, py = rayAt1m.y * z;
                    return px >= x0 && px <= x1 && py >= y0 && py <= y1;
                };
                // Skip pixels within 1e-4 m of a rectangle's border: which side they fall on
                // is a matter of rounding.
                const auto clear = [&](float x0, float x1, float y0, float y1, float z) {
                    const float px = rayAt1m.x * z, py = rayAt1m.y * z, m = 1e-4f;
                    return std::min({std::abs(px - x0), std::abs(px - x1), std::abs(py - y0),
                                     std::abs(py - y1)}) > m;
                };
                if (!clear(-0.2f, 0.05f, -0.2f, 0.05f, 0.9f) ||
                    !clear(-0.05f, 0.2f, -0.05f, 0.2f, 1.1f))
                    continue;
                const std::uint16_t expected = inside(-0.2f, 0.05f, -0.2f, 0.05f, 0.9f)   ? 11
                                               : inside(-0.05f, 0.2f, -0.05f, 0.2f, 1.1f) ? 22
                                                                                          : 0;
                ASSERT_EQ(frame.labels(y, x), expected) << "pixel " << x << "," << y;
                ASSERT_FLOAT_EQ(frame.exact_m(y, x), expected == 11   ? 0.9f
                                                     : expected == 22 ? 1.1f
                                                                      : 0.f)
                    << "pixel " << x << "," << y;
            }
    }
}

TEST(SimulatedSensor, SameSeedIsBitIdenticalAndAnotherSeedDiffers) {
    const SimulatedSensor sensor;  // every term nominal
    const std::vector<LabelledMesh> scene{frontalRect(-2.f, 2.f, -2.f, 2.f, 2.0f, 1),
                                          boxMesh({-0.15f, -0.1f, 1.f}, {0.1f, 0.2f, 1.2f}, 2),
                                          turnedPlane(1.4f, 70.f * kDegree, 0.3f, 0.1f, 3)};
    const SimulatedFrame a = sensor.render(scene, kSeed);
    const SimulatedFrame b = sensor.render(scene, kSeed);
    const SimulatedFrame c = sensor.render(scene, kSeed + 1);
    EXPECT_EQ(cv::norm(a.depth_mm, b.depth_mm, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(a.labels, b.labels, cv::NORM_INF), 0.0);
    // Quantisation snaps many readings to the same level whatever the noise, so a quarter.
    const int differing = cv::countNonZero(a.depth_mm != c.depth_mm);
    EXPECT_GT(differing, cv::countNonZero(a.exact_m) / 4) << "another seed changes readings";
    // Ground truth does not depend on the seed.
    EXPECT_EQ(cv::norm(a.exact_m, c.exact_m, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(a.labels, c.labels, cv::NORM_INF), 0.0);
}

TEST(SimulatedSensor, MeshesReachingBehindTheCameraAreClippedNotDropped) {
    // A floor 0.5 m below the camera from 1 m behind it to 6 m ahead: the visible part must
    // render exactly (z = 0.5 fy / (v - cy) on the floor y = 0.5).
    LabelledMesh floor;
    floor.label = 5;
    addQuad(floor, {-3.f, 0.5f, -1.f}, {3.f, 0.5f, -1.f}, {3.f, 0.5f, 6.f}, {-3.f, 0.5f, 6.f});
    const SimulatedSensor sensor(Intrinsics::kinectV1(), NoiseModel::none());
    const SimulatedFrame frame = sensor.render({floor}, kSeed);
    const Intrinsics k = sensor.intrinsics();
    for (int y = 300; y < k.height_px; y += 11) {  // the floor ends at 6 m, row 287.5
        const float expected_m = 0.5f * k.fy_px / (static_cast<float>(y) - k.cy_px);
        EXPECT_NEAR(frame.exact_m(y, 320), expected_m, 1e-4f * expected_m) << "row " << y;
        EXPECT_EQ(frame.labels(y, 320), 5) << "row " << y;
    }
    EXPECT_EQ(frame.exact_m(100, 320), 0.f) << "above the horizon nothing is rendered";
}

// ---------------------------------------------------------------------------------------------
// Missing readings and edge effects

TEST(SimulatedSensor, NoReadingWhereNothingWasRenderedWithLateralNoiseOff) {
    NoiseModel noise;             // nominal, flying pixels included ...
    noise.lateral = false;        // ... the one term that moves silhouettes outwards is off
    noise.flyingPixelRate = 1.f;  // flying pixels only ever move readings between surfaces
    const SimulatedSensor sensor(Intrinsics::kinectV1(), noise);
    const SimulatedFrame frame =
        sensor.render({boxMesh({-0.1f, -0.1f, 0.8f}, {0.1f, 0.1f, 0.9f}, 1),
                       frontalRect(-0.4f, 0.4f, -0.3f, 0.3f, 1.5f, 2)},
                      kSeed);
    const int stray = cv::countNonZero((frame.exact_m == 0.f) & (frame.depth_mm != 0));
    EXPECT_EQ(stray, 0);
    EXPECT_GT(cv::countNonZero(frame.depth_mm), 60000);  // the wall is ~307 x 230 px
}

TEST(SimulatedSensor, LateralNoiseOnlyAddsReadingsWithinThreeSigmaOfTheSilhouette) {
    NoiseModel noise;  // nominal: lateral 0.8 px
    const SimulatedSensor sensor(Intrinsics::kinectV1(), noise);
    const SimulatedFrame frame =
        sensor.render({frontalRect(-0.2f, 0.2f, -0.15f, 0.15f, 1.0f, kPlaneLabel)}, kSeed);
    const int reach_px = static_cast<int>(std::ceil(3.f * noise.lateral_px));
    cv::Mat1b nearSilhouette;
    cv::dilate(frame.exact_m > 0.f, nearSilhouette,
               cv::getStructuringElement(cv::MORPH_RECT, {2 * reach_px + 1, 2 * reach_px + 1}));
    const cv::Mat1b outside = (frame.exact_m == 0.f) & (frame.depth_mm != 0);
    EXPECT_EQ(cv::countNonZero(outside & ~nearSilhouette), 0);
    // The silhouette is actually ragged: some readings outside, some holes inside.
    EXPECT_GT(cv::countNonZero(outside), 50);
    EXPECT_GT(cv::countNonZero((frame.exact_m > 0.f) & (frame.depth_mm == 0)), 50);
}

// Each pixel near an edge samples the pixel displaced by round(N(0, 0.8)) px, so the pixel just
// outside a vertical silhouette reads with probability P(N(0, 0.8) > 0.5) = 0.267, and the one
// just inside stays empty with the same probability. Asserted within +-0.05 over 1600 rows.
TEST(SimulatedSensor, LateralNoiseBlursTheSilhouetteByAbout0p8Px) {
    NoiseModel noise = NoiseModel::none();
    noise.lateral = true;
    noise.scale = 1.f;
    const SimulatedSensor sensor(Intrinsics::kinectV1(), noise);
    const double expected = 0.5 * std::erfc(0.5 / (noise.lateral_px * std::numbers::sqrt2));
    int outsideReads = 0, insideEmpty = 0, rows = 0;
    for (std::uint64_t seed = 0; seed < 20; ++seed) {
        const SimulatedFrame frame =
            sensor.render({frontalRect(-0.2f, 0.2f, -0.15f, 0.15f, 1.0f, kPlaneLabel)}, seed);
        for (int y = 200; y < 280; ++y, ++rows) {
            int first = 0;
            while (frame.labels(y, first) == 0) ++first;
            outsideReads += frame.depth_mm(y, first - 1) != 0;
            insideEmpty += frame.depth_mm(y, first) == 0;
        }
    }
    EXPECT_NEAR(static_cast<double>(outsideReads) / rows, expected, 0.05);
    EXPECT_NEAR(static_cast<double>(insideEmpty) / rows, expected, 0.05);
}

// Thin ribbons standing on a ground plane, as a tuft looks to the sensor: every blade that is
// in view gets pixels with its own label, and none of its pixels carries another label where
// it is the only surface in front of the ground.
TEST(SimulatedSensor, EveryBladeOfATuftIsRenderedWithItsOwnLabel) {
    std::vector<LabelledMesh> scene;
    LabelledMesh ground;
    ground.label = 0;
    addQuad(ground, {-1.f, 0.3f, 0.5f}, {1.f, 0.3f, 0.5f}, {1.f, 0.3f, 2.f}, {-1.f, 0.3f, 2.f});
    scene.push_back(ground);
    constexpr int kBlades = 12;
    constexpr int kSegments = 16;
    for (int b = 0; b < kBlades; ++b) {
        LabelledMesh blade;
        blade.label = static_cast<std::uint16_t>(b + 1);
        const glm::vec3 root{-0.22f + 0.04f * b, 0.3f, 0.9f};
        const float halfWidth_m = 0.003f;  // 6 mm wide: ~3.8 px at 0.9 m
        for (int s = 0; s < kSegments; ++s) {
            const float t0 = static_cast<float>(s) / kSegments,
                        t1 = static_cast<float>(s + 1) / kSegments;
            const auto at = [&](float t) {
                return root + glm::vec3{0.f, -0.3f * t, 0.05f * t * t};
            };
            const float w0 = halfWidth_m * (1.f - 0.8f * t0), w1 = halfWidth_m * (1.f - 0.8f * t1);
            addQuad(blade, at(t0) - glm::vec3{w0, 0, 0}, at(t0) + glm::vec3{w0, 0, 0},
                    at(t1) + glm::vec3{w1, 0, 0}, at(t1) - glm::vec3{w1, 0, 0});
        }
        scene.push_back(blade);
    }
    const SimulatedFrame frame = SimulatedSensor().render(scene, kSeed);
    std::vector<int> pixels(kBlades + 1, 0);
    for (int y = 0; y < frame.labels.rows; ++y)
        for (int x = 0; x < frame.labels.cols; ++x) ++pixels.at(frame.labels(y, x));
    for (int b = 1; b <= kBlades; ++b)
        EXPECT_GT(pixels[b], 300) << "blade " << b;  // ~0.33 m x 4 mm mean width at 0.9 m
    // Blades stand 4 cm apart and straight up: each column of a blade's root row is that blade.
    const Intrinsics k = Intrinsics::kinectV1();
    for (int b = 0; b < kBlades; ++b) {
        const glm::vec2 rootPx = k.project({-0.22f + 0.04f * b, 0.29f, 0.9f});
        EXPECT_EQ(frame.labels(static_cast<int>(std::lround(rootPx.y)),
                               static_cast<int>(std::lround(rootPx.x))),
                  b + 1)
            << "blade " << b + 1 << " at " << rootPx.x << "," << rootPx.y;
    }
}

TEST(SimulatedSensor, FlyingPixelsLieBetweenSurfacesOnEdgesAtTheConfiguredRate) {
    NoiseModel noise = NoiseModel::none();
    noise.flyingPixels = true;
    noise.scale = 1.f;
    noise.flyingPixelRate = 0.3f;
    noise.minDepth_m = 0.4f;
    noise.maxDepth_m = 8.f;
    const SimulatedSensor sensor(Intrinsics::kinectV1(), noise);
    const SimulatedFrame frame =
        sensor.render({boxMesh({-0.15f, -0.1f, 0.9f}, {0.15f, 0.1f, 1.f}, 1),
                       frontalRect(-1.f, 1.f, -1.f, 1.f, 1.6f, 2)},
                      kSeed);
    const cv::Mat1b candidates = flyingCandidates(frame.exact_m);
    const int candidateCount = cv::countNonZero(candidates);
    int flying = 0;
    for (int y = 0; y < frame.depth_mm.rows; ++y)
        for (int x = 0; x < frame.depth_mm.cols; ++x) {
            const std::uint16_t d = frame.depth_mm(y, x);
            if (d == exactMillimetres(frame.exact_m(y, x))) continue;
            ++flying;
            ASSERT_TRUE(candidates(y, x)) << "flying pixel off an edge at " << x << "," << y;
            ASSERT_GE(d, 900 - 1) << x << "," << y;
            ASSERT_LE(d, 1600 + 1) << x << "," << y;
        }
    // Binomial(candidates, 0.3): allow 4 standard deviations either way.
    const double expected = noise.flyingPixelRate * candidateCount;
    const double sd = std::sqrt(expected * (1.0 - noise.flyingPixelRate));
    ASSERT_GT(candidateCount, 500);
    EXPECT_NEAR(flying, expected, 4.0 * sd) << "candidates " << candidateCount;
}

TEST(SimulatedSensor,
     ProjectorShadowLiesLeftOfAForegroundBoxWithWidthBaselineTimesFocalTimesInverseDepthGap) {
    const float zForeground_m = 1.0f, zWall_m = 1.5f;
    const std::vector<LabelledMesh> scene{
        boxMesh({-0.1f, -0.1f, zForeground_m}, {0.1f, 0.1f, 1.1f}, 1),
        frontalRect(-1.f, 1.f, -1.f, 1.f, zWall_m, 2)};
    const Intrinsics k = Intrinsics::kinectV1();
    const double expectedWidth_px =
        0.075 * k.fx_px * (1.0 / zForeground_m - 1.0 / zWall_m);  // 14.4
    // Exact shadows alone, then the full nominal model (ragged band, hence the looser bound).
    NoiseModel nominal;
    nominal.flyingPixels = false;  // flying pixels on the box's own border would shorten runs
    for (const auto& [noise, tolerance_px] :
         {std::pair{onlyShadows(), 1.0}, std::pair{nominal, 3.0}}) {
        const SimulatedFrame frame = SimulatedSensor(k, noise).render(scene, kSeed);
        double dropped = 0.;
        int rows = 0;
        for (int y = 200; y <= 280; ++y, ++rows) {  // box rows, away from its top and bottom
            int firstBox = 0;
            while (firstBox < k.width_px && frame.labels(y, firstBox) != 1) ++firstBox;
            int lastBox = k.width_px - 1;
            while (lastBox > 0 && frame.labels(y, lastBox) != 1) --lastBox;
            ASSERT_LT(firstBox, lastBox);
            // Missing readings from twice the expected width left of the box to just inside it:
            // counting them, rather than a run, tolerates the ragged band lateral noise makes.
            const int from = firstBox - static_cast<int>(2 * expectedWidth_px);
            for (int x = std::max(from, 0); x < firstBox + 3; ++x)
                dropped += frame.depth_mm(y, x) == 0;
            // No band on the right: the wall beside the box's right edge reads, and so do the
            // pixels inside it.
            for (int x = lastBox - 2; x <= lastBox + 3 + static_cast<int>(expectedWidth_px); ++x)
                EXPECT_NE(frame.depth_mm(y, x), 0) << "row " << y << " column " << x;
        }
        EXPECT_NEAR(dropped / rows, expectedWidth_px, tolerance_px)
            << "flying pixels " << noise.flyingPixels << " lateral " << noise.lateral;
    }
}

TEST(SimulatedSensor, GrazingSurfacesDropOutBeyondMaxIncidence) {
    NoiseModel noise = NoiseModel::none();
    noise.grazingDropout = true;
    noise.maxIncidence_deg = 80.f;
    const SimulatedSensor sensor(Intrinsics::kinectV1(), noise);
    // Turned 82 deg: across the image the incidence runs from ~53 to ~90 deg.
    const SimulatedFrame frame =
        sensor.render({turnedPlane(1.5f, 82.f * kDegree, 1.5f, 0.3f, kPlaneLabel)}, kSeed);
    int dropped = 0, kept = 0;
    for (int y = 0; y < frame.depth_mm.rows; ++y)
        for (int x = 0; x < frame.depth_mm.cols; ++x) {
            if (frame.exact_m(y, x) <= 0.f) continue;
            const bool grazing = frame.incidence_rad(y, x) > 80.f * kDegree;
            ASSERT_EQ(frame.depth_mm(y, x) == 0, grazing)
                << x << "," << y << " incidence " << frame.incidence_rad(y, x) / kDegree << " deg";
            (grazing ? dropped : kept) += 1;
        }
    EXPECT_GT(dropped, 1000);
    EXPECT_GT(kept, 1000);
    // Switched off, the same surface reads everywhere.
    noise.grazingDropout = false;
    const SimulatedFrame all =
        SimulatedSensor(Intrinsics::kinectV1(), noise)
            .render({turnedPlane(1.5f, 82.f * kDegree, 1.5f, 0.3f, kPlaneLabel)}, kSeed);
    EXPECT_EQ(cv::countNonZero(all.depth_mm), cv::countNonZero(all.exact_m));
}

TEST(SimulatedSensor, DepthOutsideTheWorkingRangeReadsZero) {
    const SimulatedSensor sensor;  // 0.4 .. 8 m
    EXPECT_EQ(cv::countNonZero(
                  sensor.render({frontalRect(-1.f, 1.f, -1.f, 1.f, 0.3f, 1)}, kSeed).depth_mm),
              0);
    EXPECT_EQ(cv::countNonZero(
                  sensor.render({frontalRect(-9.f, 9.f, -9.f, 9.f, 9.f, 1)}, kSeed).depth_mm),
              0);
    const SimulatedFrame inRange =
        sensor.render({frontalRect(-9.f, 9.f, -9.f, 9.f, 4.f, 1)}, kSeed);
    double lo = 0., hi = 0.;
    cv::minMaxLoc(inRange.depth_mm, &lo, &hi);
    EXPECT_LE(hi, 8000.);
    EXPECT_GT(cv::countNonZero(inRange.depth_mm), 300000);
}

// ---------------------------------------------------------------------------------------------
// Preconditions

TEST(SimulatedSensor, InvalidIntrinsicsThrowInvalidArgumentNamingTheField) {
    Intrinsics bad = Intrinsics::kinectV1();
    bad.fx_px = -1.f;
    try {
        SimulatedSensor sensor(bad);
        FAIL() << "negative fx accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("fx_px"), std::string::npos) << e.what();
    }
    bad = Intrinsics::kinectV1();
    bad.height_px = 0;
    EXPECT_THROW(SimulatedSensor{bad}, std::invalid_argument);
}

TEST(SimulatedSensor, InvalidNoiseModelThrowsInvalidArgumentNamingTheField) {
    const auto problemOf = [](NoiseModel m) -> std::string {
        try {
            SimulatedSensor sensor(Intrinsics::kinectV1(), m);
        } catch (const std::invalid_argument& e) {
            return e.what();
        }
        return {};
    };
    NoiseModel m;
    m.flyingPixelRate = 1.5f;
    EXPECT_NE(problemOf(m).find("flyingPixelRate"), std::string::npos) << problemOf(m);
    m = {};
    m.baseline_m = 0.f;
    EXPECT_NE(problemOf(m).find("baseline_m"), std::string::npos) << problemOf(m);
    m = {};
    m.lateral_px = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(problemOf(m).find("lateral_px"), std::string::npos) << problemOf(m);
    m = {};
    m.minDepth_m = 3.f;
    m.maxDepth_m = 2.f;
    EXPECT_NE(problemOf(m).find("minDepth_m"), std::string::npos) << problemOf(m);
    EXPECT_EQ(problemOf(NoiseModel{}), "");
    EXPECT_EQ(problemOf(NoiseModel::none()), "");
}

TEST(SimulatedSensor, MalformedMeshThrowsInvalidArgumentNamingTheMeshAndTriangle) {
    const SimulatedSensor sensor;
    LabelledMesh mesh = frontalRect(-0.1f, 0.1f, -0.1f, 0.1f, 1.f, 4);
    mesh.triangles.push_back({0, 1, 9});
    try {
        (void)sensor.render({frontalRect(-1.f, 1.f, -1.f, 1.f, 2.f, 1), mesh}, kSeed);
        FAIL() << "out-of-range index accepted";
    } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("mesh 1"), std::string::npos) << what;
        EXPECT_NE(what.find("triangle 2"), std::string::npos) << what;
    }
    LabelledMesh nanMesh = frontalRect(-0.1f, 0.1f, -0.1f, 0.1f, 1.f, 4);
    nanMesh.positions_m[2].z = std::numeric_limits<float>::infinity();
    EXPECT_THROW((void)sensor.render({nanMesh}, kSeed), std::invalid_argument);
}

}  // namespace
