#include "viewer/window.h"

#include "gpu/vulkan_error.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <cstdlib>

namespace pt::viewer {
namespace {

std::string lastGlfwError;

void onGlfwError(int, const char* description) { lastGlfwError = description ? description : "unknown GLFW error"; }

bool isSet(const char* name) {
    const char* v = std::getenv(name);
    return v && *v;
}

} // namespace

bool Input::any() const {
    return leftDrag != glm::vec2(0.0f) || panDrag != glm::vec2(0.0f) || rightDrag != glm::vec2(0.0f) ||
           scroll != 0.0f || !keys.empty();
}

std::string missingDisplayReason() {
    if (!isSet("DISPLAY") && !isSet("WAYLAND_DISPLAY")) return "no display (DISPLAY and WAYLAND_DISPLAY are not set)";
    return "";
}

Window::Window(int width, int height, const std::string& title) {
    if (std::string why = missingDisplayReason(); !why.empty()) throw NoDisplayError(why);
    glfwSetErrorCallback(onGlfwError);
    if (!glfwInit()) throw NoDisplayError("cannot open the display (" + lastGlfwError + ")");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw NoDisplayError("GLFW found no Vulkan loader to present with");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw NoDisplayError("cannot create a window (" + lastGlfwError + ")");
    }
    glfwSetWindowUserPointer(window_, this);
    glfwSetCursorPosCallback(window_, onCursor);
    glfwSetScrollCallback(window_, onScroll);
    glfwSetKeyCallback(window_, onKey);
}

Window::~Window() {
    if (window_) glfwDestroyWindow(window_);
    glfwTerminate();
}

std::vector<std::string> Window::requiredInstanceExtensions() {
    uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names) throw NoDisplayError("GLFW cannot present with Vulkan here (" + lastGlfwError + ")");
    return std::vector<std::string>(names, names + count);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    VkResult result = glfwCreateWindowSurface(instance, window_, nullptr, &surface);
    if (result != VK_SUCCESS)
        throw NoDisplayError("cannot create a Vulkan surface for the window (" + describeVkResult(result) + ")");
    return surface;
}

glm::ivec2 Window::framebufferSize() const {
    glm::ivec2 size;
    glfwGetFramebufferSize(window_, &size.x, &size.y);
    return size;
}

void Window::requestSize(int width, int height) { glfwSetWindowSize(window_, width, height); }
void Window::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }
bool Window::shouldClose() const { return glfwWindowShouldClose(window_); }
bool Window::keyDown(int key) const { return glfwGetKey(window_, key) == GLFW_PRESS; }
void Window::pollEvents() { glfwPollEvents(); }
void Window::waitEvents() { glfwWaitEvents(); }

Input Window::takeInput() {
    Input taken = std::move(input_);
    input_ = Input{};
    return taken;
}

void Window::onCursor(GLFWwindow* w, double x, double y) {
    auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
    const glm::dvec2 p(x, y);
    const glm::vec2 delta = self->haveCursor_ ? glm::vec2(p - self->cursor_) : glm::vec2(0.0f);
    self->cursor_ = p;
    self->haveCursor_ = true;
    const bool shift =
        glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS)
        (shift ? self->input_.panDrag : self->input_.leftDrag) += delta;
    if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) self->input_.panDrag += delta;
    if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) self->input_.rightDrag += delta;
}

void Window::onScroll(GLFWwindow* w, double, double dy) {
    static_cast<Window*>(glfwGetWindowUserPointer(w))->input_.scroll += static_cast<float>(dy);
}

void Window::onKey(GLFWwindow* w, int key, int, int action, int mods) {
    if (action == GLFW_RELEASE || key == GLFW_KEY_UNKNOWN) return;
    static_cast<Window*>(glfwGetWindowUserPointer(w))->input_.keys.push_back({key, mods});
}

} // namespace pt::viewer
