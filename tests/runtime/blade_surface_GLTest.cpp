// The blade surface as drawn, checked on images of blades placed by hand in front of a plain
// sky: the paper's one-sided quadratic shape, a width split unevenly about the spine, a twist
// about the spine, and the width correction of distant blades (per height, orientation-aware).
// A blade in the plane z = 0 seen square-on from +Z projects affinely, so every expected edge is
// the world edge divided by the pixel size at the camera's distance.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <opencv2/core.hpp>

#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/renderer.h"
#include "placed_blades.h"

namespace meadow::runtime {
namespace {

using modeling::AnalyticShape;
using modeling::Archetype;

constexpr int kImage_px = 256;
constexpr float kFov_deg = 50.f;
// A pixel further than this from the sky colour (max over B, G, R) is blade.
constexpr int kSkyDistance = 60;
// Edges are compared with the projection of the world edge within this many pixels: one pixel of
// rasterisation (pixel centres decide coverage) and a little of tessellation (12 segments).
constexpr float kEdgeTolerance_px = 1.5f;

struct View {
    glm::vec3 camera_m;
    glm::vec3 target_m;
    [[nodiscard]] float pixelAt_m(float distance_m) const {
        return 2.f * std::tan(glm::radians(0.5f * kFov_deg)) * distance_m / kImage_px;
    }
    // Image position (x right, y down, pixel units, centres at + 0.5) of a world point.
    [[nodiscard]] glm::vec2 project(glm::vec3 p) const {
        const glm::mat4 clip = glm::perspective(glm::radians(kFov_deg), 1.f, 0.05f, 200.f) *
                               glm::lookAt(camera_m, target_m, glm::vec3(0.f, 1.f, 0.f));
        const glm::vec4 c = clip * glm::vec4(p, 1.f);
        return {(c.x / c.w * 0.5f + 0.5f) * kImage_px, (0.5f - c.y / c.w * 0.5f) * kImage_px};
    }
};

cv::Mat render(const View& view, std::vector<Archetype> archetypes,
               const std::vector<test::PlacedBlade>& blades, int msaa = 1) {
    static GlContext context;
    const SceneDescription scene = test::placedBladeScene(
        "blade_surface", view.camera_m, view.target_m, kImage_px, msaa, std::move(archetypes));
    Renderer renderer(context, scene, test::placedBlades(scene, blades));
    return renderer.renderFrame(0).image_bgr.clone();
}

bool isBlade(const cv::Mat& image, int x, int y) {
    const cv::Vec3b sky = image.at<cv::Vec3b>(0, 0);
    return cv::norm(image.at<cv::Vec3b>(y, x), sky, cv::NORM_INF) > kSkyDistance;
}

// Leftmost and rightmost blade pixel of row y within [x0, x1), as pixel-centre positions; x of
// -1 when the row has none.
struct RowEdges {
    float left = -1.f, right = -1.f;
    int count = 0;
};
RowEdges rowEdges(const cv::Mat& image, int y, int x0 = 0, int x1 = kImage_px) {
    RowEdges e;
    for (int x = std::max(x0, 0); x < std::min(x1, image.cols); ++x)
        if (isBlade(image, x, y)) {
            if (e.count++ == 0) e.left = static_cast<float>(x) + 0.5f;
            e.right = static_cast<float>(x) + 0.5f;
        }
    return e;
}

// A square-on view of an upright blade 0.5 m tall in the plane z = 0, 1.2 m away.
constexpr float kHeight_m = 0.5f, kWidth_m = 0.1f;
const View kSquareOn{{0.f, 0.25f, 1.2f}, {0.f, 0.25f, 0.f}};

// The image row whose centre shows height fraction v of the blade, and the pixel size there.
int rowAt(float v) {
    return static_cast<int>(std::floor(kSquareOn.project({0.f, v * kHeight_m, 0.f}).y));
}
float heightFractionOfRow(int y) {
    const float top = kSquareOn.project({0.f, kHeight_m, 0.f}).y;
    const float base = kSquareOn.project({0.f, 0.f, 0.f}).y;
    return (base - (static_cast<float>(y) + 0.5f)) / (base - top);
}
float columnOf(float x_m) { return kSquareOn.project({x_m, 0.f, 0.f}).x; }

TEST(BladeSurfaceGLTest, OneSidedQuadraticKeepsOneEdgeStraightAndCurvesTheOtherIntoIt) {
    Archetype oneSided =
        test::uprightArchetype(kHeight_m, kWidth_m, AnalyticShape::OneSidedQuadratic);
    const cv::Mat image = render(kSquareOn, {oneSided}, {{}});
    // The paper's t = u - u v^2: the left edge (u = 0) stays at -w/2, the right edge moves from
    // +w/2 to -w/2 as 1/2 - v^2.
    for (int y = rowAt(0.9f); y <= rowAt(0.1f); ++y) {
        const float v = heightFractionOfRow(y);
        const RowEdges e = rowEdges(image, y);
        ASSERT_GT(e.count, 0) << "row " << y << " (v " << v << ") shows no blade";
        EXPECT_NEAR(e.left, columnOf(-0.5f * kWidth_m), kEdgeTolerance_px) << "v " << v;
        EXPECT_NEAR(e.right, columnOf((0.5f - v * v) * kWidth_m), kEdgeTolerance_px) << "v " << v;
    }
    // meadow's symmetric quadratic draws both edges curving in: its left edge at v = 0.9 lies
    // 0.405 w (9 px) inside the one-sided shape's.
    const cv::Mat symmetric = render(
        kSquareOn, {test::uprightArchetype(kHeight_m, kWidth_m, AnalyticShape::Quadratic)}, {{}});
    EXPECT_GT(rowEdges(symmetric, rowAt(0.9f)).left,
              columnOf(-0.5f * kWidth_m) + 3.f * kEdgeTolerance_px);
}

TEST(BladeSurfaceGLTest, LeftWidthFractionSplitsTheWidthUnevenlyAboutTheSpine) {
    for (AnalyticShape shape : {AnalyticShape::Quad, AnalyticShape::Triangle}) {
        for (float left : {0.2f, 0.5f, 0.75f}) {
            Archetype a = test::uprightArchetype(kHeight_m, kWidth_m, shape);
            a.leftWidthFraction = left;
            const cv::Mat image = render(kSquareOn, {a}, {{}});
            for (int y = rowAt(0.8f); y <= rowAt(0.1f); ++y) {
                const float v = heightFractionOfRow(y);
                const float local_m = kWidth_m * (shape == AnalyticShape::Quad ? 1.f : 1.f - v);
                const RowEdges e = rowEdges(image, y);
                ASSERT_GT(e.count, 0) << "row " << y;
                EXPECT_NEAR(e.left, columnOf(-left * local_m), kEdgeTolerance_px)
                    << toString(shape) << " left share " << left << " v " << v;
                EXPECT_NEAR(e.right, columnOf((1.f - left) * local_m), kEdgeTolerance_px)
                    << toString(shape) << " left share " << left << " v " << v;
            }
        }
    }
}

TEST(BladeSurfaceGLTest, TwistTurnsTheWidthAboutTheSpineFromBaseToTip) {
    Archetype twisted = test::uprightArchetype(kHeight_m, kWidth_m, AnalyticShape::Quad);
    twisted.twistAtTip_rad = 0.5f * std::numbers::pi_v<float>;
    const cv::Mat image = render(kSquareOn, {twisted}, {{}});
    const float pixel_m = kSquareOn.pixelAt_m(1.2f);
    // The width direction turns by (pi / 2) v about the upright spine: it spans w cos(pi v / 2)
    // across the image. The nearer half of the turned blade is up to 4 % larger in perspective.
    for (float v : {0.2f, 0.4f, 0.6f, 0.8f}) {
        const int y = rowAt(v);
        const float vRow = heightFractionOfRow(y);
        const RowEdges e = rowEdges(image, y);
        const float expected_px =
            kWidth_m * std::cos(0.5f * std::numbers::pi_v<float> * vRow) / pixel_m;
        EXPECT_NEAR(e.right - e.left + 1.f, expected_px, 2.f + 0.04f * expected_px) << "v " << vRow;
    }
    const cv::Mat flat =
        render(kSquareOn, {test::uprightArchetype(kHeight_m, kWidth_m, AnalyticShape::Quad)}, {{}});
    const RowEdges flatTop = rowEdges(flat, rowAt(0.8f));
    EXPECT_NEAR(flatTop.right - flatTop.left + 1.f, kWidth_m / pixel_m, 2.f);
}

// Distant blades far thinner than a pixel: eight triangle blades 1 m tall and 4 mm wide at the
// base, 12 m away (0.09 px wide at the base, 23 px tall), 0.6 m apart, turned by `turn_rad`
// from facing the camera. No multisampling, so a pixel is blade only where a triangle covers its
// centre.
struct DistantRow {
    int rowsShown = 0, rowsTotal = 0;  // rows between base and tip with >= 1 blade pixel
    int widestRow_px = 0;
};
std::vector<DistantRow> distantBlades(float turn_rad, float minWidthCheckFromTip = 0.05f) {
    const View view{{0.f, 0.5f, 12.f}, {0.f, 0.5f, 0.f}};
    const Archetype thin = test::uprightArchetype(1.f, 0.004f, AnalyticShape::Triangle);
    std::vector<test::PlacedBlade> blades;
    for (int i = 0; i < 8; ++i)
        // Sub-pixel offsets differ from blade to blade (0.6 m is 13.7 px).
        blades.push_back({glm::vec3(-2.1f + 0.6f * static_cast<float>(i), 0.f, 0.f), turn_rad, 0});
    const cv::Mat image = render(view, {thin}, blades);
    std::vector<DistantRow> out;
    for (const test::PlacedBlade& b : blades) {
        const glm::vec2 base = view.project(b.root_m),
                        tip = view.project(b.root_m + glm::vec3(0, 1, 0));
        DistantRow r;
        const int x = static_cast<int>(std::floor(base.x));
        // Rows strictly inside the blade's extent, leaving out the last few percent at the tip.
        const float cut = minWidthCheckFromTip * (base.y - tip.y);
        for (int y = static_cast<int>(std::ceil(tip.y + cut)); y < static_cast<int>(base.y) - 1;
             ++y) {
            const RowEdges e = rowEdges(image, y, x - 3, x + 4);
            ++r.rowsTotal;
            r.rowsShown += e.count > 0;
            r.widestRow_px = std::max(r.widestRow_px, e.count);
        }
        out.push_back(r);
    }
    return out;
}

TEST(BladeSurfaceGLTest, WidthCorrectionKeepsDistantTaperedBladesWholeToTheirTips) {
    for (float turn_deg : {0.f, 60.f}) {
        const std::vector<DistantRow> rows = distantBlades(glm::radians(turn_deg));
        for (std::size_t i = 0; i < rows.size(); ++i) {
            // Every row from the base to near the tip shows the blade (a sub-pixel triangle without
            // the correction shows a few dots), and no row more than two pixels of it: widened to
            // one pixel on screen, turned or not, and no further.
            EXPECT_GE(rows[i].rowsShown, rows[i].rowsTotal - 1)
                << "blade " << i << " turned " << turn_deg << " deg: " << rows[i].rowsShown
                << " of " << rows[i].rowsTotal << " rows";
            EXPECT_GT(rows[i].rowsTotal, 15);
            EXPECT_LE(rows[i].widestRow_px, 2) << "blade " << i << " turned " << turn_deg;
        }
    }
}

}  // namespace
}  // namespace meadow::runtime
