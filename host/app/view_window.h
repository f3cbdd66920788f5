// `vkray view`'s window (GLFW): opened on the display, with no client API of
// its own (Vulkan presents to it), its input turned into ViewEvents.
#pragma once

#include "app/view_events.h"
#include "gpu/presenter.h"

#include <string>
#include <vector>

struct GLFWwindow;

namespace vkray {

class ViewWindow {
public:
    // A window of the image's size, not resizable. Throws Error when there is
    // no display (naming DISPLAY and WAYLAND_DISPLAY, and `render --watch`)
    // or the window system cannot give Vulkan a surface.
    ViewWindow(int width, int height, const std::string& title);
    ~ViewWindow();
    ViewWindow(const ViewWindow&) = delete;
    ViewWindow& operator=(const ViewWindow&) = delete;

    // The Vulkan instance extensions its surface needs.
    std::vector<std::string> surfaceExtensions() const;
    gpu::SurfaceMaker surfaceMaker() const;

    void setTitle(const std::string& title);
    // The input since the last call, after waiting up to `seconds` for some
    // (0: none). A close of the window arrives as `key q`.
    std::vector<ViewEvent> events(double seconds = 0);
    // From any thread: makes a waiting events() return.
    static void wake();

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace vkray
