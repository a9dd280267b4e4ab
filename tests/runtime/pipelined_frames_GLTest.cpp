// Renderer::renderFrames, the pipelined path, against renderFrame, the synchronous one: the same
// scene rendered both ways gives the same images and counts frame by frame, frames arrive in
// order, and a call without images or without frames still works.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "meadow/runtime/culling.h"
#include "meadow/runtime/gl_context.h"
#include "meadow/runtime/physics.h"
#include "meadow/runtime/renderer.h"
#include "support/scene_files.h"

namespace meadow::runtime {
namespace {

constexpr int kFrames = 8;  // more than the frames in flight, so the ring wraps around

// A small meadow in a strong gusty wind with a collider, so every frame differs.
SceneDescription windyScene(const std::string& name) {
    const auto dir = test::freshTestDirectory(name);
    return loadSceneDescription(test::writeSmallMeadow(
        dir, {{"wind", {{"wave_amplitude_m_s", 6}, {"frequency_hz", 2}}},
              {"colliders", {{{"center_m", {0.1, 0.05, 0.0}}, {"radius_m", 0.15}}}}}));
}

// The windy scene with the renderer's own physics and culling passes, as `meadow render` runs it.
struct WindyRenderer {
    explicit WindyRenderer(const std::string& name) : renderer(context, windyScene(name)) {
        installPhysicsPass(renderer, context);
        installCullingPass(renderer, context);
    }
    GlContext context;
    Renderer renderer;
};

bool sameBytes(const cv::Mat& a, const cv::Mat& b) {
    return a.type() == b.type() && a.size() == b.size() && a.isContinuous() && b.isContinuous() &&
           std::memcmp(a.data, b.data, a.total() * a.elemSize()) == 0;
}

std::vector<RenderedFrame> renderPipelined(Renderer& renderer, int first, int count,
                                           bool wantImages) {
    std::vector<RenderedFrame> frames;
    renderer.renderFrames(first, count, wantImages,
                          [&](RenderedFrame&& f) { frames.push_back(std::move(f)); });
    return frames;
}

TEST(PipelinedFramesGLTest, ImagesAndCountsEqualTheSynchronousPathFrameByFrameInOrder) {
    const SceneDescription scene = windyScene("pipelined_frames_equal");
    GlContext context;
    Renderer synchronous(context, scene), pipelined(context, scene);
    for (Renderer* r : {&synchronous, &pipelined}) {
        installPhysicsPass(*r, context);
        installCullingPass(*r, context);
    }
    const std::vector<RenderedFrame> frames = renderPipelined(pipelined, 0, kFrames, true);
    ASSERT_EQ(frames.size(), static_cast<std::size_t>(kFrames));
    bool anyImageChanged = false;
    cv::Mat previous;
    for (int i = 0; i < kFrames; ++i) {
        SCOPED_TRACE("frame " + std::to_string(i));
        const RenderedFrame expected = synchronous.renderFrame(i);
        const RenderedFrame& got = frames[static_cast<std::size_t>(i)];
        const FrameStats &e = expected.stats, &g = got.stats;
        EXPECT_EQ(g.frame, i) << "frames must arrive in order";
        EXPECT_EQ(g.time_s, e.time_s);
        EXPECT_EQ(g.bladesTotal, e.bladesTotal);
        EXPECT_EQ(g.bladesDrawn, e.bladesDrawn);
        EXPECT_EQ(g.culledOrientation, e.culledOrientation);
        EXPECT_EQ(g.culledFrustum, e.culledFrustum);
        EXPECT_EQ(g.culledDistance, e.culledDistance);
        EXPECT_EQ(g.culledOcclusion, e.culledOcclusion);
        EXPECT_LT(g.bladesDrawn, g.bladesTotal) << "nothing was culled";
        EXPECT_GT(g.gpuCulling_ms, 0.0);
        EXPECT_GT(g.frame_ms, 0.0);
        EXPECT_TRUE(sameBytes(got.image_bgr, expected.image_bgr))
            << "pipelined " << got.image_bgr.cols << "x" << got.image_bgr.rows << " type "
            << got.image_bgr.type() << ", synchronous " << expected.image_bgr.cols << "x"
            << expected.image_bgr.rows << " type " << expected.image_bgr.type();
        if (!previous.empty() && !sameBytes(previous, got.image_bgr)) anyImageChanged = true;
        previous = got.image_bgr;
    }
    EXPECT_TRUE(anyImageChanged) << "the wind should move the blades between frames";
}

TEST(PipelinedFramesGLTest, NoFramesDeliversNothingAndWithoutImagesStatsStillArrive) {
    WindyRenderer windy("pipelined_frames_no_images");
    Renderer& renderer = windy.renderer;
    EXPECT_TRUE(renderPipelined(renderer, 0, 0, true).empty());
    EXPECT_TRUE(renderPipelined(renderer, 0, 0, false).empty());
    // Fewer frames than the ring holds, then a second call that continues the simulation.
    for (const auto& [first, count] : {std::pair{0, 2}, std::pair{2, 5}}) {
        const std::vector<RenderedFrame> frames = renderPipelined(renderer, first, count, false);
        ASSERT_EQ(frames.size(), static_cast<std::size_t>(count));
        for (int k = 0; k < count; ++k) {
            const RenderedFrame& f = frames[static_cast<std::size_t>(k)];
            const FrameStats& s = f.stats;
            SCOPED_TRACE("frame " + std::to_string(first + k));
            EXPECT_EQ(s.frame, first + k);
            EXPECT_TRUE(f.image_bgr.empty()) << "no image was asked for";
            EXPECT_EQ(s.bladesTotal, renderer.bladeCount());
            EXPECT_EQ(s.bladesDrawn + s.culledOrientation + s.culledFrustum + s.culledDistance +
                          s.culledOcclusion,
                      s.bladesTotal);
            EXPECT_GT(s.bladesDrawn, 0u);
            EXPECT_GT(s.gpuDraw_ms, 0.0);
            EXPECT_GT(s.frame_ms, 0.0);
        }
    }
}

TEST(PipelinedFramesGLTest, ACallbackThatThrowsDropsTheFramesInFlightAndTheNextCallStartsClean) {
    WindyRenderer windy("pipelined_frames_throw");
    Renderer& renderer = windy.renderer;
    struct Stop {};
    EXPECT_THROW(renderer.renderFrames(0, 6, true, [](RenderedFrame&&) { throw Stop{}; }), Stop);
    const std::vector<RenderedFrame> frames = renderPipelined(renderer, 6, 4, true);
    ASSERT_EQ(frames.size(), 4u);
    for (int k = 0; k < 4; ++k) {
        EXPECT_EQ(frames[static_cast<std::size_t>(k)].stats.frame, 6 + k);
        EXPECT_FALSE(frames[static_cast<std::size_t>(k)].image_bgr.empty());
    }
}

TEST(PipelinedFramesGLTest, NegativeCountIsAPreconditionFailure) {
    const SceneDescription scene = windyScene("pipelined_frames_negative");
    GlContext context;
    Renderer renderer(context, scene);
    EXPECT_THROW(renderer.renderFrames(0, -1, false, [](RenderedFrame&&) {}),
                 std::invalid_argument);
}

}  // namespace
}  // namespace meadow::runtime
