#pragma once
// The GLFW window of `pt view`: creation (with a one-line reason when there is no display),
// its Vulkan surface, and the mouse and keyboard input gathered between frames.
#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>
#include <vector>

struct GLFWwindow;

namespace pt::viewer {

// No window can be shown here (no display, GLFW or the Vulkan loader cannot use it, no device
// can present to it). The message is one line, without the "pt: error: " prefix.
class NoDisplayError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct KeyPress {
    int key = 0;  // GLFW_KEY_*
    int mods = 0; // GLFW_MOD_*
};

// Input since the previous takeInput(): drags in window pixels (x right, y down).
struct Input {
    glm::vec2 leftDrag{0.0f}; // without shift
    glm::vec2 panDrag{0.0f};  // middle button, or shift + left
    glm::vec2 rightDrag{0.0f};
    float scroll = 0.0f;        // wheel clicks, positive away from the user
    std::vector<KeyPress> keys; // presses and auto-repeats
    bool any() const;
};

class Window {
public:
    // Throws NoDisplayError when there is no display or GLFW cannot open a window on it.
    Window(int width, int height, const std::string& title);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    // Instance extensions the surface needs (glfwGetRequiredInstanceExtensions).
    static std::vector<std::string> requiredInstanceExtensions();
    VkSurfaceKHR createSurface(VkInstance instance);

    glm::ivec2 framebufferSize() const;
    void requestSize(int width, int height);
    void setTitle(const std::string& title);
    bool shouldClose() const;
    bool keyDown(int key) const;
    void pollEvents();
    void waitEvents();
    Input takeInput();

private:
    static void onCursor(GLFWwindow* w, double x, double y);
    static void onScroll(GLFWwindow* w, double dx, double dy);
    static void onKey(GLFWwindow* w, int key, int scancode, int action, int mods);

    GLFWwindow* window_ = nullptr;
    Input input_;
    glm::dvec2 cursor_{0.0};
    bool haveCursor_ = false;
};

// "" when a display looks available, else why not (DISPLAY and WAYLAND_DISPLAY both unset).
std::string missingDisplayReason();

} // namespace pt::viewer
