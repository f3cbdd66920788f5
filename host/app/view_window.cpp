#include "app/view_window.h"

#include "util/error.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <cstring>

namespace vkray {

namespace {

std::string lastGlfwError;

void rememberError(int, const char* description) {
    lastGlfwError = description ? description : "";
}

// Input gathered by the callbacks, handed out by events().
struct Input {
    std::vector<ViewEvent> events;
    double x = 0, y = 0;  // the cursor where the last drag step ended
    int button = -1;      // the button held (GLFW_MOUSE_BUTTON_LEFT or _RIGHT), or -1
};

Input& inputOf(GLFWwindow* window) {
    return *static_cast<Input*>(glfwGetWindowUserPointer(window));
}

ViewEvent keyEvent(const std::string& key) {
    ViewEvent e;
    e.kind = ViewEvent::Kind::Key;
    e.key = key;
    return e;
}

bool hasDisplay() {
    for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"}) {
        const char* value = std::getenv(name);
        if (value && *value) return true;
    }
    return false;
}

}  // namespace

ViewWindow::ViewWindow(int width, int height, const std::string& title) {
    if (!hasDisplay())
        throw Error(
            "vkray view needs a display, and neither DISPLAY nor WAYLAND_DISPLAY is set; "
            "run it in a desktop session (or under xvfb-run), or use `vkray render "
            "--watch` to re-render a PNG whenever the scene changes");
    glfwSetErrorCallback(rememberError);
    if (!glfwInit())
        throw Error("vkray view cannot open the display (DISPLAY or WAYLAND_DISPLAY): " +
                    lastGlfwError + "; use `vkray render --watch` to re-render a PNG instead");
    if (!glfwVulkanSupported()) {
        glfwTerminate();
        throw Error("vkray view: the window system offers Vulkan no surface (" + lastGlfwError +
                    "); install the Vulkan loader and a driver (on Debian: libvulkan1 and "
                    "mesa-vulkan-drivers), or use `vkray render --watch`");
    }
    glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window_) {
        glfwTerminate();
        throw Error("vkray view cannot open a " + std::to_string(width) + "x" +
                    std::to_string(height) + " window: " + lastGlfwError);
    }
    glfwSetWindowUserPointer(window_, new Input);
    glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned int c) {
        if (c != 0 && c < 128 && std::strchr("rp1234cdsq", int(c)))
            inputOf(w).events.push_back(keyEvent(std::string(1, char(c))));
    });
    glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int) {
        if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS)
            inputOf(w).events.push_back(keyEvent("esc"));
    });
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
        Input& input = inputOf(w);
        if (action == GLFW_PRESS &&
            (button == GLFW_MOUSE_BUTTON_LEFT || button == GLFW_MOUSE_BUTTON_RIGHT)) {
            input.button = button;
            glfwGetCursorPos(w, &input.x, &input.y);
        } else if (action == GLFW_RELEASE && button == input.button) {
            input.button = -1;
        }
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
        Input& input = inputOf(w);
        if (input.button < 0) return;
        ViewEvent e;
        e.kind = ViewEvent::Kind::Drag;
        e.rightButton = input.button == GLFW_MOUSE_BUTTON_RIGHT;
        e.dx = x - input.x;
        e.dy = y - input.y;
        input.x = x;
        input.y = y;
        // Steps of one drag in a row are one move: the camera changes once.
        if (!input.events.empty() && input.events.back().kind == ViewEvent::Kind::Drag &&
            input.events.back().rightButton == e.rightButton) {
            input.events.back().dx += e.dx;
            input.events.back().dy += e.dy;
        } else {
            input.events.push_back(e);
        }
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double y) {
        ViewEvent e;
        e.kind = ViewEvent::Kind::Wheel;
        e.steps = y;
        inputOf(w).events.push_back(e);
    });
}

ViewWindow::~ViewWindow() {
    delete &inputOf(window_);
    glfwDestroyWindow(window_);
    glfwTerminate();
}

std::vector<std::string> ViewWindow::surfaceExtensions() const {
    std::uint32_t count = 0;
    const char** names = glfwGetRequiredInstanceExtensions(&count);
    if (!names)
        throw Error("vkray view: the window system names no Vulkan surface extensions (" +
                    lastGlfwError + ")");
    return std::vector<std::string>(names, names + count);
}

gpu::SurfaceMaker ViewWindow::surfaceMaker() const {
    GLFWwindow* window = window_;
    return [window](void* instance) {
        VkSurfaceKHR surface = VK_NULL_HANDLE;
        const VkResult result =
            glfwCreateWindowSurface(static_cast<VkInstance>(instance), window, nullptr, &surface);
        if (result != VK_SUCCESS)
            throw Error("vkray view: cannot make the window's Vulkan surface (VkResult " +
                        std::to_string(int(result)) + "): " + lastGlfwError);
        std::uint64_t handle = 0;
        static_assert(sizeof handle == sizeof surface);
        std::memcpy(&handle, &surface, sizeof handle);
        return handle;
    };
}

void ViewWindow::setTitle(const std::string& title) {
    glfwSetWindowTitle(window_, title.c_str());
}

std::vector<ViewEvent> ViewWindow::events(double seconds) {
    if (seconds > 0)
        glfwWaitEventsTimeout(seconds);
    else
        glfwPollEvents();
    Input& input = inputOf(window_);
    if (glfwWindowShouldClose(window_)) {
        glfwSetWindowShouldClose(window_, GLFW_FALSE);
        input.events.push_back(keyEvent("q"));
    }
    std::vector<ViewEvent> events;
    events.swap(input.events);
    return events;
}

void ViewWindow::wake() {
    glfwPostEmptyEvent();
}

}  // namespace vkray
