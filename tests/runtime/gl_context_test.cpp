// The headless context, the GL object owners and the shader loader.
#include "meadow/runtime/gl_context.h"

#include <gtest/gtest.h>

#include <type_traits>

#include "gl/gl_object.h"
#include "gl/shader_program.h"
#include "meadow/runtime/error.h"

namespace meadow::runtime {
namespace {

TEST(GlContextGLTest, CreatesOpenGl45CoreContextAndNamesTheDriver) {
    GlContext context;
    EXPECT_FALSE(context.vendor().empty());
    EXPECT_FALSE(context.renderer().empty());
    GLint major = 0, minor = 0, profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45) << context.version();
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT) << context.version();
    EXPECT_NO_THROW(context.checkErrors("a fresh context"));
}

TEST(GlContextGLTest, DebugOutputTurnsAGlErrorIntoRuntimeError) {
    GlContext context(GlContextOptions{.debugOutput = true});
    glBindBuffer(GL_ARRAY_BUFFER, 0xdeadu);  // not a buffer name: GL_INVALID_OPERATION
    EXPECT_THROW(context.checkErrors("binding a made-up buffer name"), RuntimeError);
    EXPECT_NO_THROW(context.checkErrors("after the error was reported"));
}

TEST(GlObjectGLTest, MoveTransfersOwnershipAndLeavesZero) {
    static_assert(!std::is_copy_constructible_v<gl::Buffer>);
    static_assert(!std::is_copy_assignable_v<gl::Buffer>);
    static_assert(std::is_nothrow_move_constructible_v<gl::Buffer>);
    static_assert(std::is_nothrow_move_assignable_v<gl::Buffer>);
    static_assert(!std::is_convertible_v<gl::Buffer, gl::Texture>);
    GlContext context;
    gl::Buffer a = gl::Buffer::create();
    const GLuint name = a.id();
    ASSERT_NE(name, 0u);
    EXPECT_TRUE(glIsBuffer(name));
    gl::Buffer b(std::move(a));
    EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state is the point
    EXPECT_EQ(b.id(), name);
    gl::Buffer c;
    c = std::move(b);
    EXPECT_EQ(c.id(), name);
    EXPECT_EQ(b.id(), 0u);  // NOLINT(bugprone-use-after-move)
    { gl::Buffer scoped = std::move(c); }
    EXPECT_FALSE(glIsBuffer(name)) << "the destructor of the last owner deletes the name";
    gl::Texture t = gl::Texture::create(GL_TEXTURE_2D);
    const GLuint released = t.release();
    EXPECT_EQ(t.id(), 0u);
    EXPECT_TRUE(glIsTexture(released));
    glDeleteTextures(1, &released);
    context.checkErrors("GlObject moves");
}

TEST(GlObjectGLTest, SyncMovesLikeTheOtherOwnersAndItsFenceSignals) {
    static_assert(!std::is_copy_constructible_v<gl::Sync>);
    static_assert(!std::is_copy_assignable_v<gl::Sync>);
    static_assert(std::is_nothrow_move_constructible_v<gl::Sync>);
    static_assert(std::is_nothrow_move_assignable_v<gl::Sync>);
    GlContext context;
    gl::Sync a = gl::Sync::fence();
    const GLsync fence = a.get();
    ASSERT_NE(fence, nullptr);
    EXPECT_TRUE(glIsSync(fence));
    gl::Sync b(std::move(a));
    EXPECT_EQ(a.get(),
              nullptr);  // NOLINT(bugprone-use-after-move): the moved-from state is the point
    EXPECT_EQ(b.get(), fence);
    const GLenum status = glClientWaitSync(b.get(), GL_SYNC_FLUSH_COMMANDS_BIT, 10'000'000'000ull);
    EXPECT_TRUE(status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED) << status;
    { gl::Sync scoped = std::move(b); }
    EXPECT_FALSE(glIsSync(fence)) << "the destructor of the last owner deletes the fence";
    gl::Sync c = gl::Sync::fence();
    const GLsync released = c.release();
    EXPECT_EQ(c.get(), nullptr);
    EXPECT_TRUE(glIsSync(released));
    glDeleteSync(released);
    context.checkErrors("Sync moves");
}

TEST(ShaderProgramGLTest, AssemblesVersionDefinesSharedTypesAndLineDirectives) {
    gl::ProgramSource source{.label = "test",
                             .stages = {{GL_COMPUTE_SHADER, "shared/blade_types.h"}},
                             .commonFiles = {},
                             .defines = {{"MEADOW_TEST_DEFINE", "3"}}};
    std::vector<std::string> parts;
    const std::string text = gl::assembleStageSource(source, source.stages[0], &parts);
    EXPECT_EQ(text.rfind("#version 450 core\n", 0), 0u);
    EXPECT_NE(text.find("#define MEADOW_TEST_DEFINE 3\n"), std::string::npos);
    EXPECT_NE(text.find("#line 1 0\n"), std::string::npos);
    EXPECT_NE(text.find("struct BladeGpu"), std::string::npos);
    ASSERT_EQ(parts.size(), 2u);
    EXPECT_EQ(parts[0], "shared/blade_types.h");
}

TEST(ShaderProgramGLTest, CompileErrorNamesTheFileAndTheLog) {
    GlContext context;
    // blade_types.h alone has no main(): compiling it as a stage must fail with its name.
    gl::ProgramSource source{.label = "broken",
                             .stages = {{GL_COMPUTE_SHADER, "shared/blade_types.h"}},
                             .commonFiles = {},
                             .defines = {}};
    try {
        gl::ShaderProgram program(source);
        FAIL() << "a program without main() linked";
    } catch (const RuntimeError& e) {
        EXPECT_NE(std::string(e.what()).find("shaders/shared/blade_types.h"), std::string::npos)
            << e.what();
    }
}

}  // namespace
}  // namespace meadow::runtime
