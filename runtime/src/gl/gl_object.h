#pragma once
// Move-only owners of OpenGL names (style.md §4): exactly one owner per name, the destructor
// deletes it, a moved-from object holds 0, release() gives ownership away for interop. Distinct
// Traits make distinct types, so a Texture can never be passed where a Buffer is expected.
#include <utility>

#include "gl_api.h"

namespace meadow::runtime::gl {

template <class Traits>
class GlObject {
public:
    GlObject() noexcept = default;
    explicit GlObject(GLuint id) noexcept : id_(id) {}
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;
    GlObject(GlObject&& o) noexcept : id_(std::exchange(o.id_, 0)) {}
    // Swap: the name this object held is deleted when `o` goes out of scope.
    GlObject& operator=(GlObject&& o) noexcept {
        std::swap(id_, o.id_);
        return *this;
    }
    ~GlObject() {
        if (id_) Traits::destroy(id_);
    }

    // A new GL name from Traits::create(args...) (glCreate*, so the object exists at once and
    // the direct-state-access functions may be used on it).
    template <class... Args>
    [[nodiscard]] static GlObject create(Args... args) {
        return GlObject(Traits::create(args...));
    }

    [[nodiscard]] GLuint id() const noexcept { return id_; }
    explicit operator bool() const noexcept { return id_ != 0; }
    [[nodiscard]] GLuint release() noexcept { return std::exchange(id_, 0); }

private:
    GLuint id_ = 0;
};

struct BufferTraits {
    static GLuint create() {
        GLuint id = 0;
        glCreateBuffers(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct TextureTraits {
    static GLuint create(GLenum target) {
        GLuint id = 0;
        glCreateTextures(target, 1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
struct RenderbufferTraits {
    static GLuint create() {
        GLuint id = 0;
        glCreateRenderbuffers(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteRenderbuffers(1, &id); }
};
struct FramebufferTraits {
    static GLuint create() {
        GLuint id = 0;
        glCreateFramebuffers(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct VertexArrayTraits {
    static GLuint create() {
        GLuint id = 0;
        glCreateVertexArrays(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct QueryTraits {
    static GLuint create(GLenum target) {
        GLuint id = 0;
        glCreateQueries(target, 1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};
struct ShaderTraits {
    static GLuint create(GLenum stage) { return glCreateShader(stage); }
    static void destroy(GLuint id) { glDeleteShader(id); }
};
struct ProgramTraits {
    static GLuint create() { return glCreateProgram(); }
    static void destroy(GLuint id) { glDeleteProgram(id); }
};

using Buffer = GlObject<BufferTraits>;
using Texture = GlObject<TextureTraits>;
using Renderbuffer = GlObject<RenderbufferTraits>;
using Framebuffer = GlObject<FramebufferTraits>;
using VertexArray = GlObject<VertexArrayTraits>;
using Query = GlObject<QueryTraits>;
using Shader = GlObject<ShaderTraits>;
using Program = GlObject<ProgramTraits>;

// A fence (glFenceSync). GLsync is a pointer, not a GLuint name, so it has its own owner with
// the same rules: move-only, a moved-from Sync holds 0 (null), the destructor deletes it.
class Sync {
public:
    Sync() noexcept = default;
    explicit Sync(GLsync sync) noexcept : sync_(sync) {}
    Sync(const Sync&) = delete;
    Sync& operator=(const Sync&) = delete;
    Sync(Sync&& o) noexcept : sync_(std::exchange(o.sync_, nullptr)) {}
    Sync& operator=(Sync&& o) noexcept {
        std::swap(sync_, o.sync_);
        return *this;
    }
    ~Sync() {
        if (sync_) glDeleteSync(sync_);
    }

    // A fence after every command issued so far; it signals when they have all completed.
    [[nodiscard]] static Sync fence() {
        return Sync(glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0));
    }

    [[nodiscard]] GLsync get() const noexcept { return sync_; }
    explicit operator bool() const noexcept { return sync_ != nullptr; }
    [[nodiscard]] GLsync release() noexcept { return std::exchange(sync_, nullptr); }

private:
    GLsync sync_ = nullptr;
};

}  // namespace meadow::runtime::gl
