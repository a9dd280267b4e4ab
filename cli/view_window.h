#pragma once
// The window of `meadow view`: GLFW, an OpenGL 4.5 core context made current on this thread, and
// the input the viewer reads each frame. One per process (GLFW is initialised and terminated
// with it).
#include <glm/vec2.hpp>
#include <string>
#include <vector>

struct GLFWwindow;

namespace meadow::cli {

class ViewWindow {
public:
    // Throws meadow::Error (one line, ending with what to do) when there is no display to open a
    // window on, or the display offers no OpenGL 4.5 core context.
    ViewWindow(int width_px, int height_px, bool debugContext);
    ~ViewWindow();
    ViewWindow(const ViewWindow&) = delete;
    ViewWindow& operator=(const ViewWindow&) = delete;

    [[nodiscard]] bool closeRequested() const;
    void requestClose();
    void setTitle(const std::string& title);
    // vsync on: one frame per display refresh; off: as fast as the GPU goes.
    void setSwapInterval(int interval);
    // The back buffer's size in pixels (larger than the window's on a scaled display).
    [[nodiscard]] glm::ivec2 framebufferSize_px() const;
    // Shows the back buffer, then collects the input of the events that came meanwhile.
    void present();

    [[nodiscard]] bool isKeyDown(int glfwKey) const;
    // Keys pressed since the last call, in order (key repeat left out).
    [[nodiscard]] std::vector<int> takePressedKeys();
    // Cursor movement since the last call while the left or right mouse button was held.
    [[nodiscard]] glm::vec2 takeLookDelta_px();

private:
    static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
    static void onCursor(GLFWwindow* window, double x_px, double y_px);

    GLFWwindow* window_ = nullptr;
    std::vector<int> pressedKeys_;
    glm::dvec2 lastCursor_px_{0.0};
    bool haveCursor_ = false;
    glm::vec2 lookDelta_px_{0.f};
};

}  // namespace meadow::cli
