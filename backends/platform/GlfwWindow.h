// A GLFW window (X11 or Wayland), shared by the gl-glfw and vulkan-glfw backends. libglfw.so.3
// is opened at run time, so machines without it or without a display still run the headless
// backends. Nothing here is specific to one API: the GL context and the Vulkan surface are made
// by the backends through symbol().
#pragma once
#include "fe/gdi/Device.h"
#include "fe/gdi/Image.h"
#include <cstdint>
#include <vector>

namespace fe::platform {

class GlfwWindow {
public:
    enum class Api { OpenGL45, Vulkan };

    // A hidden window (offscreen work needs none; prepare() shows it). OpenGL45: owning a 4.5
    // core context (a debug context when `debug`); Vulkan: no client API, for a surface.
    // Throws gdi::Error saying why not (no display, libglfw3 missing, no Vulkan loader, ...).
    GlfwWindow(Api api, bool debug);
    ~GlfwWindow();
    GlfwWindow(const GlfwWindow&) = delete;
    GlfwWindow& operator=(const GlfwWindow&) = delete;

    void* handle() const { return window_; }  // GLFWwindow*
    // A GLFW entry point, for what belongs to one API (contexts, swaps, Vulkan surfaces).
    void* symbol(const char* name) const;
    template <class T>
    T function(const char* name) const {
        return reinterpret_cast<T>(symbol(name));
    }

    struct Size {
        uint32_t width = 0, height = 0;
    };
    // Shows the window on the first call (`firstShow` says so) and sizes it to width x height,
    // waiting for the window system; returns the framebuffer size it really has (a window
    // manager may refuse a size).
    Size prepare(uint32_t width, uint32_t height, bool* firstShow = nullptr);
    Size framebufferSize() const;
    // Handles pending window events and samples the input; false once the user has closed the window.
    bool poll();
    // The input as of the last poll(): mouse, keys, and the wheel and text since the one before.
    const gdi::InputState& input() const { return input_; }
    // What the window shows on screen, width x height from its top-left (the last presented
    // image's size; 0 before the first present, an error), RGBA8 rows top-down, read back from
    // the X server (XGetImage), not from the API that drew it.
    gdi::Image read(uint32_t width, uint32_t height) const;

private:
    void release();
    void* lib_ = nullptr;
    void* window_ = nullptr;
    bool initialised_ = false;
    bool shown_ = false;
    gdi::InputState input_;
    float wheel_ = 0;  // gathered by GLFW's callbacks between polls
    std::string text_;
    uint8_t presses_[size_t(gdi::Key::Count)] = {};
    std::vector<std::string> dropped_;
};

}  // namespace fe::platform
