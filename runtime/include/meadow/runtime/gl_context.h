#pragma once
// A headless OpenGL 4.5 core context through EGL (Mesa's surfaceless platform, or an EGL device
// for vendor drivers without a window system). cli/ (or a test) creates one and passes it down by
// reference; nothing in meadow keeps a global context. Everything GL happens on the thread that
// created it. adoptCurrent() wraps a window's context instead (`meadow view`), so the same passes
// draw into a window.
#include <memory>
#include <string>
#include <string_view>

namespace meadow::runtime {

struct GlContextOptions {
#ifdef NDEBUG
    bool debugOutput = false;
#else
    bool debugOutput = true;  // KHR_debug: GL errors become RuntimeError at checkErrors()
#endif
};

class GlContext {
public:
    // Throws RuntimeError when no EGL display offers an OpenGL 4.5 core context.
    explicit GlContext(GlContextOptions options = {});
    // Wraps the OpenGL 4.5 core context current on this thread (a window's, made by GLFW), which
    // its creator keeps owning: the destructor leaves it current and alive. Throws RuntimeError
    // when none is current or it offers less than 4.5 core.
    [[nodiscard]] static GlContext adoptCurrent(GlContextOptions options = {});
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    [[nodiscard]] const std::string& vendor() const;
    [[nodiscard]] const std::string& renderer() const;
    [[nodiscard]] const std::string& version() const;  // GL_VERSION
    [[nodiscard]] bool debugOutput() const;

    // Throws RuntimeError naming `where` if GL reported an error since the last call (glGetError,
    // and with debug output on, every GL_DEBUG_TYPE_ERROR message).
    void checkErrors(std::string_view where) const;
    // Blocks until every submitted GL command has completed.
    void finish() const;

private:
    struct AdoptCurrentTag {};
    GlContext(AdoptCurrentTag, GlContextOptions options);
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace meadow::runtime
