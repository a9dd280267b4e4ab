// Headless EGL + OpenGL 4.5 core context, or an adopted window context (see gl_context.h).
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "gl/gl_api.h"
#include "meadow/runtime/error.h"
#include "meadow/runtime/gl_context.h"

namespace meadow::runtime {
namespace {

constexpr EGLint kGlMajorVersion = 4;
constexpr EGLint kGlMinorVersion = 5;
// At most this many EGL devices are probed on the device platform (vendor drivers, no window).
constexpr EGLint kMaxEglDevices = 16;
// Debug messages kept for checkErrors(); more than this in one frame is one message too many.
constexpr std::size_t kMaxKeptDebugMessages = 8;

const char* const kInstallHint =
    "install an EGL driver with OpenGL 4.5 core (Debian: apt-get install libegl1 libgl1 "
    "libegl-mesa0 libgl1-mesa-dri for Mesa llvmpipe, or the vendor driver)";

bool hasExtension(const char* extensions, const char* name) {
    if (!extensions) return false;
    const std::size_t n = std::strlen(name);
    for (const char* p = extensions; (p = std::strstr(p, name)) != nullptr; p += n)
        if ((p == extensions || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

std::string eglErrorName(EGLint code) {
    switch (code) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        default:
            return "EGL error " + std::to_string(code);
    }
}

// Candidate displays in order of preference: Mesa's surfaceless platform (llvmpipe or a GPU
// through its render node), then each EGL device (NVIDIA without X), then the default display.
std::vector<EGLDisplay> candidateDisplays() {
    std::vector<EGLDisplay> displays;
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (getPlatformDisplay && hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d =
            getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d != EGL_NO_DISPLAY) displays.push_back(d);
    }
    auto queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (getPlatformDisplay && queryDevices &&
        hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[kMaxEglDevices];
        EGLint count = 0;
        if (queryDevices(kMaxEglDevices, devices, &count))
            for (EGLint i = 0; i < count; ++i) {
                EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                if (d != EGL_NO_DISPLAY) displays.push_back(d);
            }
    }
    if (EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY); d != EGL_NO_DISPLAY)
        displays.push_back(d);
    return displays;
}

}  // namespace

struct GlContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    std::string vendor, renderer, version;
    bool debugOutput = false;
    mutable std::mutex debugMutex;  // the callback may run on a driver thread
    mutable std::vector<std::string> debugErrors;

    // Tries one display; on success the context is current and true is returned. `why` collects
    // the reason of each failure for the final error message.
    bool tryDisplay(EGLDisplay d, bool debug, std::string& why) {
        EGLint major = 0, minor = 0;
        if (!eglInitialize(d, &major, &minor)) {
            why += " [eglInitialize: " + eglErrorName(eglGetError()) + "]";
            return false;
        }
        const char* displayExtensions = eglQueryString(d, EGL_EXTENSIONS);
        if (!hasExtension(displayExtensions, "EGL_KHR_surfaceless_context")) {
            why += " [display without EGL_KHR_surfaceless_context]";
            eglTerminate(d);
            return false;
        }
        if (!eglBindAPI(EGL_OPENGL_API)) {
            why += " [no desktop OpenGL API]";
            eglTerminate(d);
            return false;
        }
        EGLConfig config = nullptr;
        if (!hasExtension(displayExtensions, "EGL_KHR_no_config_context")) {
            const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
            EGLint count = 0;
            if (!eglChooseConfig(d, configAttributes, &config, 1, &count) || count == 0) {
                why += " [no OpenGL config]";
                eglTerminate(d);
                return false;
            }
        }
        const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                            kGlMajorVersion,
                                            EGL_CONTEXT_MINOR_VERSION,
                                            kGlMinorVersion,
                                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                            EGL_CONTEXT_OPENGL_DEBUG,
                                            debug ? EGL_TRUE : EGL_FALSE,
                                            EGL_NONE};
        EGLContext c = eglCreateContext(d, config, EGL_NO_CONTEXT, contextAttributes);
        if (c == EGL_NO_CONTEXT) {
            why += " [no OpenGL 4.5 core context: " + eglErrorName(eglGetError()) + "]";
            eglTerminate(d);
            return false;
        }
        if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
            why += " [eglMakeCurrent: " + eglErrorName(eglGetError()) + "]";
            eglDestroyContext(d, c);
            eglTerminate(d);
            return false;
        }
        display = d;
        context = c;
        return true;
    }

    // Reads the current context's strings, checks it offers 4.5 and turns debug output on.
    void describeCurrent(GlContextOptions options);

    static void APIENTRY onDebugMessage(GLenum /*source*/, GLenum type, GLuint /*id*/,
                                        GLenum severity, GLsizei length, const GLchar* message,
                                        const void* user) {
        // Only errors (and high-severity undefined behaviour) become exceptions; performance
        // notes from the driver are not failures.
        if (type != GL_DEBUG_TYPE_ERROR &&
            !(type == GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR && severity == GL_DEBUG_SEVERITY_HIGH))
            return;
        const auto* self = static_cast<const Impl*>(user);
        std::lock_guard lock(self->debugMutex);
        if (self->debugErrors.size() < kMaxKeptDebugMessages)
            self->debugErrors.emplace_back(
                message, length >= 0 ? static_cast<std::size_t>(length) : std::strlen(message));
    }
};

GlContext::GlContext(GlContextOptions options) : impl_(std::make_unique<Impl>()) {
    std::string why;
    const std::vector<EGLDisplay> displays = candidateDisplays();
    bool ok = false;
    for (EGLDisplay d : displays)
        if ((ok = impl_->tryDisplay(d, options.debugOutput, why))) break;
    if (!ok)
        throw RuntimeError("no EGL display offers OpenGL " + std::to_string(kGlMajorVersion) + "." +
                           std::to_string(kGlMinorVersion) + " core (" +
                           std::to_string(displays.size()) + " displays tried:" + why + "); " +
                           kInstallHint);
    impl_->describeCurrent(options);
}

GlContext::GlContext(AdoptCurrentTag, GlContextOptions options) : impl_(std::make_unique<Impl>()) {
    // Without a current context GLVND's dispatch answers every query with 0.
    if (!glGetString(GL_VERSION))
        throw RuntimeError(
            "GlContext::adoptCurrent: no OpenGL context is current on this thread; make the "
            "window's context current first");
    impl_->describeCurrent(options);
}

GlContext GlContext::adoptCurrent(GlContextOptions options) {
    return GlContext(AdoptCurrentTag{}, options);
}

void GlContext::Impl::describeCurrent(GlContextOptions options) {
    auto glString = [](GLenum name) {
        const GLubyte* s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("unknown");
    };
    vendor = glString(GL_VENDOR);
    renderer = glString(GL_RENDERER);
    version = glString(GL_VERSION);
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < kGlMajorVersion * 10 + kGlMinorVersion)
        throw RuntimeError("driver '" + renderer + "' gives OpenGL " + version +
                           ", meadow needs 4.5 core; " + kInstallHint);
    if (options.debugOutput) {
        debugOutput = true;
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);  // so an error names the call that caused it
        glDebugMessageCallback(&Impl::onDebugMessage, this);
    }
}

GlContext::~GlContext() {
    if (impl_->debugOutput) glDebugMessageCallback(nullptr, nullptr);
    if (impl_->context == EGL_NO_CONTEXT) return;  // adopted: its window destroys it
    eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(impl_->display, impl_->context);
    // The display is not terminated: EGL displays are shared per process, and terminating one
    // would pull the rug from another GlContext on the same display.
    eglReleaseThread();
}

const std::string& GlContext::vendor() const { return impl_->vendor; }
const std::string& GlContext::renderer() const { return impl_->renderer; }
const std::string& GlContext::version() const { return impl_->version; }
bool GlContext::debugOutput() const { return impl_->debugOutput; }

void GlContext::checkErrors(std::string_view where) const {
    std::string message;
    for (GLenum e = glGetError(); e != GL_NO_ERROR; e = glGetError()) {
        char code[32];
        std::snprintf(code, sizeof code, " GL error 0x%04x", e);
        message += code;
    }
    {
        std::lock_guard lock(impl_->debugMutex);
        for (const std::string& m : impl_->debugErrors) message += " [" + m + "]";
        impl_->debugErrors.clear();
    }
    if (!message.empty())
        throw RuntimeError("meadow::runtime: OpenGL error in " + std::string(where) + ":" +
                           message + " (driver '" + impl_->renderer +
                           "'); this is a bug in meadow, please report it");
}

void GlContext::finish() const { glFinish(); }

}  // namespace meadow::runtime
