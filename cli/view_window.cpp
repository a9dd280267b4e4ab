#include "view_window.h"

#include <GLFW/glfw3.h>

#include <cstdlib>
#include <string>
#include <utility>

#include "meadow/runtime/error.h"

namespace meadow::cli {
namespace {

constexpr const char* kHeadlessHint = "use meadow render for headless frames";

bool isSet(const char* variable) {
    const char* value = std::getenv(variable);
    return value && *value;
}

std::string lastGlfwError() {
    const char* description = nullptr;
    glfwGetError(&description);
    return description ? description : "no reason given";
}

}  // namespace

ViewWindow::ViewWindow(int width_px, int height_px, bool debugContext) {
    // GLFW would say "X11: The DISPLAY environment variable is missing"; say it for people.
    if (!isSet("DISPLAY") && !isSet("WAYLAND_DISPLAY"))
        throw runtime::RuntimeError(
            std::string("view: no display to open a window on (DISPLAY is not set); ") +
            kHeadlessHint);
    if (!glfwInit())
        throw runtime::RuntimeError("view: no display to open a window on (" + lastGlfwError() +
                                    "); " + kHeadlessHint);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, debugContext ? GLFW_TRUE : GLFW_FALSE);
    // The renderer draws into its own multisampled target and copies the resolved image here: a
    // blit into a multisampled back buffer is not allowed, and depth is not needed.
    glfwWindowHint(GLFW_SAMPLES, 0);
    glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glfwWindowHint(GLFW_STENCIL_BITS, 0);
    // The renderer's image has a fixed size; a resized window would only stretch it.
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    window_ = glfwCreateWindow(width_px, height_px, "meadow view", nullptr, nullptr);
    if (!window_) {
        const std::string why = lastGlfwError();
        glfwTerminate();
        throw runtime::RuntimeError("view: cannot open an OpenGL 4.5 core window (" + why + "); " +
                                    kHeadlessHint);
    }
    glfwMakeContextCurrent(window_);
    glfwSetWindowUserPointer(window_, this);
    glfwSetKeyCallback(window_, &ViewWindow::onKey);
    glfwSetCursorPosCallback(window_, &ViewWindow::onCursor);
}

ViewWindow::~ViewWindow() {
    glfwDestroyWindow(window_);
    glfwTerminate();
}

bool ViewWindow::closeRequested() const { return glfwWindowShouldClose(window_); }
void ViewWindow::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }
void ViewWindow::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }
void ViewWindow::setSwapInterval(int interval) { glfwSwapInterval(interval); }

glm::ivec2 ViewWindow::framebufferSize_px() const {
    glm::ivec2 size{0};
    glfwGetFramebufferSize(window_, &size.x, &size.y);
    return size;
}

void ViewWindow::present() {
    glfwSwapBuffers(window_);
    glfwPollEvents();
}

bool ViewWindow::isKeyDown(int glfwKey) const { return glfwGetKey(window_, glfwKey) == GLFW_PRESS; }

std::vector<int> ViewWindow::takePressedKeys() { return std::exchange(pressedKeys_, {}); }

glm::vec2 ViewWindow::takeLookDelta_px() { return std::exchange(lookDelta_px_, glm::vec2(0.f)); }

void ViewWindow::onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
    auto* self = static_cast<ViewWindow*>(glfwGetWindowUserPointer(window));
    if (action == GLFW_PRESS) self->pressedKeys_.push_back(key);
}

void ViewWindow::onCursor(GLFWwindow* window, double x_px, double y_px) {
    auto* self = static_cast<ViewWindow*>(glfwGetWindowUserPointer(window));
    const glm::dvec2 cursor{x_px, y_px};
    const bool looking = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS ||
                         glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if (looking && self->haveCursor_)
        self->lookDelta_px_ += glm::vec2(cursor - self->lastCursor_px_);
    self->lastCursor_px_ = cursor;
    self->haveCursor_ = true;
}

}  // namespace meadow::cli
