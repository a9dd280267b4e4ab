// Whole frames as `meadow render` makes them: physics -> culling -> draw, with wind and a sphere
// rolling through. Grass stays where it grows and the sky stays sky, the blade state the draw
// read is finite and above ground, and the same scene gives the same frames twice.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <iostream>
#include <opencv2/core.hpp>
#include <vector>

#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/renderer.h"
#include "physics_scene_pass.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

constexpr int kFrames = 12;  // 0.4 s at 30 Hz: long enough for wind and sphere to bend blades

// A 1 m square of grass seen from the side and above (the lower half of the image), under strong
// wind, with a sphere rolling across it.
SceneDescription windyMeadow() {
    const nlohmann::json extra = {
        {"wind",
         {{"direction", {1, 0, 0}},
          {"wave_amplitude_m_s", 1},
          {"source_m", {0, 0, 0}},
          {"source_amplitude_m_s", 1.5},
          {"source_radius_m", 1}}},
        {"colliders",
         {{{"center_m", {-0.4, 0.1, 0}}, {"radius_m", 0.15}, {"velocity_m_s", {1, 0, 0}}}}}};
    return loadSceneDescription(
        test::writeSmallMeadow(test::freshTestDirectory("render_full_frame"), extra));
}

// The renderer's own physics pass, then a read-back of the blade buffer it wrote: the state the
// culling and the draw of this frame read.
class PhysicsThenReadBack final : public BladeComputePass {
public:
    PhysicsThenReadBack(GlContext& context, std::vector<gpu::BladeGpu>& blades)
        : physics_(makePhysicsComputePass(context)), blades_(blades) {}
    void run(const PassInputs& in) override {
        physics_->run(in);
        blades_.resize(in.gpu.bladeCount);
        glGetNamedBufferSubData(in.gpu.blades.id(), 0,
                                static_cast<GLsizeiptr>(blades_.size() * sizeof(gpu::BladeGpu)),
                                blades_.data());
    }

private:
    std::unique_ptr<BladeComputePass> physics_;
    std::vector<gpu::BladeGpu>& blades_;
};

struct FramesOfARun {
    std::vector<cv::Mat> images;
    std::vector<FrameStats> stats;
    std::vector<gpu::BladeGpu> blades;  // after the last frame's physics
    std::size_t bladeCount = 0;
};

FramesOfARun renderWindyMeadow(GlContext& context, const SceneDescription& scene) {
    FramesOfARun run;
    Renderer renderer(context, scene);
    renderer.setPhysicsPass(std::make_unique<PhysicsThenReadBack>(context, run.blades));
    installCullingPass(renderer, context);
    for (int f = 0; f < kFrames; ++f) {
        RenderedFrame frame = renderer.renderFrame(f);
        run.images.push_back(frame.image_bgr.clone());
        run.stats.push_back(frame.stats);
    }
    run.bladeCount = renderer.bladeCount();
    return run;
}

bool isGreen(const cv::Vec3b& bgr) { return test::isGreen(bgr[0], bgr[1], bgr[2]); }

TEST(RenderFullFrameGLTest, PhysicsCullingAndDrawKeepGrassOnTheGroundFiniteAndRepeatable) {
    GlContext context;
    const SceneDescription scene = windyMeadow();
    const FramesOfARun first = renderWindyMeadow(context, scene);
    const cv::Mat& image = first.images.back();
    ASSERT_EQ(image.type(), CV_8UC3);

    // Every frame: each blade drawn or culled by exactly one test, and both passes ran.
    for (int f = 0; f < kFrames; ++f) {
        const FrameStats& s = first.stats[f];
        SCOPED_TRACE("frame " + std::to_string(f));
        EXPECT_EQ(s.bladesDrawn + s.culledOrientation + s.culledFrustum + s.culledDistance +
                      s.culledOcclusion,
                  s.bladesTotal);
        EXPECT_GT(s.bladesDrawn, s.bladesTotal / 2);
        EXPECT_GT(s.gpuCulling_ms, 0.0);
    }

    // Sky: the top rows are exactly the clear colour. The tallest tips, drawn to their ends by
    // the width correction, reach row 4 of 64 at rest and only sink under wind and gravity.
    const cv::Vec3b sky(static_cast<uchar>(std::lround(0.9 * 255)),
                        static_cast<uchar>(std::lround(0.75 * 255)),
                        static_cast<uchar>(std::lround(0.6 * 255)));
    constexpr int kSkyRows = 4;
    for (int y = 0; y < kSkyRows; ++y)
        for (int x = 0; x < image.cols; ++x)
            ASSERT_LE(cv::norm(image.at<cv::Vec3b>(y, x), sky, cv::NORM_INF), 1.0)
                << "sky pixel at x " << x << " y " << y;
    // Grass: the band above the square's near half, where the blades stand against the far
    // ground, is mostly green (the near half shows ground through the gap the sphere pressed).
    int green = 0, total = 0;
    for (int y = image.rows / 4; y < image.rows / 2; ++y)
        for (int x = image.cols / 8; x < image.cols * 7 / 8; ++x, ++total)
            green += isGreen(image.at<cv::Vec3b>(y, x));
    std::cout << "full frame " << kFrames - 1 << ": " << green << " of " << total
              << " grass-band pixels green, " << first.stats.back().bladesDrawn << " of "
              << first.stats.back().bladesTotal << " blades drawn\n";
    EXPECT_GT(green, total / 2);

    // The blade state after the last frame: finite, tips above the local ground plane, at
    // length, and moved by the wind and the sphere (physics really ran).
    ASSERT_EQ(first.blades.size(), first.bladeCount);
    const SceneBlades rest = buildSceneBlades(scene);
    ASSERT_EQ(rest.blades.size(), first.blades.size());
    float worstBelow = 0.f, meanMove = 0.f;
    for (std::size_t i = 0; i < first.blades.size(); ++i) {
        const gpu::BladeGpu& b = first.blades[i];
        for (int k = 0; k < 4; ++k)
            ASSERT_TRUE(std::isfinite(b.v0_height[k]) && std::isfinite(b.v1_width[k]) &&
                        std::isfinite(b.v2_stiffness[k]) && std::isfinite(b.up_direction[k]))
                << "blade " << i;
        const float h = b.v0_height.w;
        worstBelow =
            std::max(worstBelow, -glm::dot(glm::vec3(b.v2_stiffness) - glm::vec3(b.v0_height),
                                           glm::vec3(b.up_direction)) /
                                     h);
        meanMove +=
            glm::distance(glm::vec3(b.v2_stiffness), glm::vec3(rest.blades[i].v2_stiffness)) / h /
            static_cast<float>(first.blades.size());
    }
    std::cout << "blade tips moved " << meanMove << " h on average; worst below ground "
              << worstBelow << " h\n";
    EXPECT_LE(worstBelow, 1e-5f);
    EXPECT_GT(meanMove, 0.02f) << "the wind did not move the blades: was physics run?";

    // Twice the same scene, the same frames, bit for bit.
    const FramesOfARun second = renderWindyMeadow(context, scene);
    for (int f = 0; f < kFrames; ++f)
        EXPECT_EQ(cv::norm(first.images[f], second.images[f], cv::NORM_INF), 0.0) << "frame " << f;
    for (std::size_t i = 0; i < first.blades.size(); ++i)
        ASSERT_EQ(first.blades[i].v2_stiffness, second.blades[i].v2_stiffness) << "blade " << i;
}

}  // namespace
}  // namespace meadow::runtime
