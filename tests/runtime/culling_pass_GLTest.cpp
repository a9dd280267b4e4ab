// The GPU culling pass (shaders/cull.comp) against its CPU reference: the same visible blades and
// the same count per test, frame after frame (the counters are reset between frames).
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <random>
#include <string>
#include <vector>

#include "culling_pass.h"
#include "culling_test_scene.h"
#include "shader_sources.h"

namespace meadow::runtime {
namespace {

template <class T>
gl::Buffer upload(const std::vector<T>& data) {
    gl::Buffer b = gl::Buffer::create();
    glNamedBufferStorage(b.id(), data.size() * sizeof(T), data.data(), GL_DYNAMIC_STORAGE_BIT);
    return b;
}

gl::Texture uploadDepth(const testing::CullScene& s) {
    gl::Texture t = gl::Texture::create(GL_TEXTURE_2D);
    glTextureStorage2D(t.id(), 1, GL_DEPTH_COMPONENT32F, static_cast<GLsizei>(s.depthWidth),
                       static_cast<GLsizei>(s.depthHeight));
    glTextureSubImage2D(t.id(), 0, 0, 0, static_cast<GLsizei>(s.depthWidth),
                        static_cast<GLsizei>(s.depthHeight), GL_DEPTH_COMPONENT, GL_FLOAT,
                        s.depth.data());
    glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return t;
}

std::vector<std::uint32_t> readVisible(const CullingPass& pass, std::uint32_t count) {
    std::vector<std::uint32_t> v(count);
    if (count)
        glGetNamedBufferSubData(pass.visibleIndices().id(), 0, count * sizeof(std::uint32_t),
                                v.data());
    std::sort(v.begin(), v.end());  // the GPU appends in whatever order the atomics fall
    return v;
}

struct Config {
    const char* name;
    CullSettings settings;
};

std::vector<Config> configs() {
    CullSettings all;
    all.maxDistance_m = 30.f;
    CullSettings none = all;
    none.orientation = none.frustum = none.distance = none.occlusion = false;
    std::vector<Config> c = {{"all tests", all}, {"none", none}};
    for (int k = 0; k < 4; ++k) {
        CullSettings one = none;
        (k == 0   ? one.orientation
         : k == 1 ? one.frustum
         : k == 2 ? one.distance
                  : one.occlusion) = true;
        c.push_back({k == 0   ? "orientation only"
                     : k == 1 ? "frustum only"
                     : k == 2 ? "distance only"
                              : "occlusion only",
                     one});
    }
    return c;
}

// Exact equality is expected: both sides run the same float expressions in the same order. A
// blade sitting within float rounding of a decision boundary (a frustum plane, a distance level)
// could in principle go either way; in this scene none does, and the test says so if one ever
// does (it prints the blade).
TEST(CullingPassGLTest, GpuCountsPerTestAndVisibleSetEqualTheCpuReferenceFrameAfterFrame) {
    GlContext context;
    const testing::CullScene scene = testing::makeCullScene(31);
    const auto bladeCount = static_cast<std::uint32_t>(scene.blades.size());
    const auto patchCount = static_cast<std::uint32_t>(scene.patches.size());
    CullingPass pass(context, bladeCount);
    const gl::Buffer blades = upload(scene.blades), patches = upload(scene.patches);
    const gl::Texture depthTexture = uploadDepth(scene);
    const CullDepth depth{depthTexture, scene.depthWidth, scene.depthHeight};
    const DepthImageView depthView{scene.depthWidth, scene.depthHeight, scene.depth};
    const CullCamera camera{scene.clipFromWorld, scene.camera_m, scene.near_m, scene.far_m};
    for (const Config& c : configs()) {
        const CullResult cpu = cullReference(
            scene.blades, scene.patches,
            packCullParams(c.settings, scene.clipFromWorld, scene.camera_m, scene.near_m,
                           scene.far_m, patchCount, scene.depthWidth, scene.depthHeight),
            &depthView);
        for (int frame = 0; frame < 3; ++frame) {
            pass.dispatch(blades, bladeCount, patches, patchCount, camera, c.settings, &depth);
            const gpu::DrawCommandGpu cmd = pass.readDrawCommand();
            const gpu::CullStatsGpu st = pass.readStats();
            SCOPED_TRACE(std::string(c.name) + ", frame " + std::to_string(frame));
            EXPECT_EQ(cmd.vertexCount, cpu.visible.size());
            EXPECT_EQ(cmd.instanceCount, 1u);
            EXPECT_EQ(cmd.firstVertex, 0u);
            EXPECT_EQ(st.culledOrientation, cpu.stats.culledOrientation);
            EXPECT_EQ(st.culledFrustum, cpu.stats.culledFrustum);
            EXPECT_EQ(st.culledDistance, cpu.stats.culledDistance);
            EXPECT_EQ(st.culledOcclusion, cpu.stats.culledOcclusion);
            const auto visible = readVisible(pass, std::min(cmd.vertexCount, bladeCount));
            std::vector<std::uint32_t> expected = cpu.visible;
            std::sort(expected.begin(), expected.end());
            EXPECT_EQ(visible, expected);
        }
        std::cout << c.name << ": visible " << cpu.visible.size() << ", orientation "
                  << cpu.stats.culledOrientation << ", frustum " << cpu.stats.culledFrustum
                  << ", distance " << cpu.stats.culledDistance << ", occlusion "
                  << cpu.stats.culledOcclusion << " of " << bladeCount << '\n';
    }
}

TEST(CullingPassGLTest, WithoutDepthTextureOcclusionIsOffAndMoreBladesThanCapacityIsRejected) {
    GlContext context;
    const testing::CullScene scene = testing::makeCullScene(32);
    const auto bladeCount = static_cast<std::uint32_t>(scene.blades.size());
    const auto patchCount = static_cast<std::uint32_t>(scene.patches.size());
    CullingPass pass(context, bladeCount);
    const gl::Buffer blades = upload(scene.blades), patches = upload(scene.patches);
    const CullCamera camera{scene.clipFromWorld, scene.camera_m, scene.near_m, scene.far_m};
    pass.dispatch(blades, bladeCount, patches, patchCount, camera, CullSettings{}, nullptr);
    EXPECT_EQ(pass.readStats().culledOcclusion, 0u);
    EXPECT_THROW(
        pass.dispatch(blades, bladeCount + 1, patches, patchCount, camera, CullSettings{}, nullptr),
        std::invalid_argument);
}

TEST(CullingPassGLTest, WritesIntoARenderersOwnBuffersWhenGivenTargets) {
    GlContext context;
    const testing::CullScene scene = testing::makeCullScene(33);
    const auto bladeCount = static_cast<std::uint32_t>(scene.blades.size());
    const auto patchCount = static_cast<std::uint32_t>(scene.patches.size());
    CullingPass pass(context, 1);  // its own buffers are too small: the targets must be used
    const gl::Buffer blades = upload(scene.blades), patches = upload(scene.patches);
    const gl::Buffer visible = upload(std::vector<std::uint32_t>(bladeCount, 0u));
    const gl::Buffer command = upload(std::vector<gpu::DrawCommandGpu>{{123u, 7u, 0u, 0u}});
    const gl::Buffer stats = upload(std::vector<gpu::CullStatsGpu>{{9u, 9u, 9u, 9u}});
    const CullCamera camera{scene.clipFromWorld, scene.camera_m, scene.near_m, scene.far_m};
    CullSettings settings;
    settings.maxDistance_m = 30.f;
    pass.dispatch(blades, bladeCount, patches, patchCount, camera, settings, nullptr,
                  CullTargets{visible, bladeCount, command, stats});
    const CullResult cpu =
        cullReference(scene.blades, scene.patches,
                      packCullParams(settings, scene.clipFromWorld, scene.camera_m, scene.near_m,
                                     scene.far_m, patchCount, 0, 0),
                      nullptr);
    gpu::DrawCommandGpu cmd{};
    glGetNamedBufferSubData(command.id(), 0, sizeof(cmd), &cmd);
    gpu::CullStatsGpu st{};
    glGetNamedBufferSubData(stats.id(), 0, sizeof(st), &st);
    EXPECT_EQ(cmd.vertexCount, cpu.visible.size());
    EXPECT_EQ(cmd.instanceCount, 1u);
    EXPECT_EQ(st.culledOrientation, cpu.stats.culledOrientation);
    EXPECT_EQ(st.culledFrustum, cpu.stats.culledFrustum);
    EXPECT_EQ(st.culledDistance, cpu.stats.culledDistance);
    EXPECT_EQ(st.culledOcclusion, 0u);
}

// Orientation culling and front gravity use bladeWidthAxis() (common_physics.glsl, compiled as
// C++ too); the draw pass builds the blade from bladeWidthDirection() (common_blade.glsl). Both
// must give the same direction, or the wrong blades would be culled as edge-on.
TEST(CullingPassGLTest, WidthAxisOfCullingMatchesTheDrawPassWidthDirectionOnTheGpu) {
    GlContext context;
    const std::string source =
        "#version 450 core\n" + std::string(detail::shaderSource("common_blade.glsl")) +
        "\nlayout(local_size_x = 64) in;\n"
        "layout(std430, binding = 0) readonly buffer In { vec4 upAngle[]; };\n"
        "layout(std430, binding = 1) writeonly buffer Out { vec4 width[]; };\n"
        "void main() { uint i = gl_GlobalInvocationID.x;\n"
        "  width[i] = vec4(bladeWidthDirection(upAngle[i].xyz, upAngle[i].w), 0.0); }\n";
    gl::Shader shader = gl::Shader::create(GL_COMPUTE_SHADER);
    const char* text = source.c_str();
    glShaderSource(shader.id(), 1, &text, nullptr);
    glCompileShader(shader.id());
    GLint ok = 0;
    glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
    ASSERT_TRUE(ok) << "common_blade.glsl did not compile on its own";
    gl::Program program = gl::Program::create();
    glAttachShader(program.id(), shader.id());
    glLinkProgram(program.id());
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    ASSERT_TRUE(ok);

    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    std::vector<glm::vec4> upAngle = {{0, 1, 0, 0}, {0, 0, 1, 1}, {0, 0, -1, 2}, {1, 0, 0, 3}};
    while (upAngle.size() < 1024) {
        const glm::vec3 up{u(rng), u(rng), u(rng)};
        if (glm::length(up) > 0.1f) upAngle.emplace_back(glm::normalize(up), 3.14159265f * u(rng));
    }
    const gl::Buffer in = upload(upAngle);
    gl::Buffer out = gl::Buffer::create();
    glNamedBufferStorage(out.id(), upAngle.size() * sizeof(glm::vec4), nullptr, 0);
    glUseProgram(program.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id());
    glDispatchCompute(static_cast<GLuint>(upAngle.size() / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> width(upAngle.size());
    glGetNamedBufferSubData(out.id(), 0, width.size() * sizeof(glm::vec4), width.data());
    for (std::size_t i = 0; i < upAngle.size(); ++i) {
        const glm::vec3 cpu = shader::bladeWidthAxis(glm::vec3(upAngle[i]), upAngle[i].w);
        EXPECT_LT(glm::distance(cpu, glm::vec3(width[i])), 1e-5f)
            << "up " << upAngle[i].x << ',' << upAngle[i].y << ',' << upAngle[i].z << " angle "
            << upAngle[i].w;
    }
}

}  // namespace
}  // namespace meadow::runtime
