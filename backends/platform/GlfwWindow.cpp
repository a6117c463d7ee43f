#include "platform/GlfwWindow.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "fe/gdi/Device.h"
#include "platform/DynamicLibrary.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <X11/Xlib.h>  // after Device.h: Xlib defines macros such as None

namespace fe::platform {

namespace {

// The GLFW entry points every window uses, loaded once: GLFW is process-wide.
struct Glfw {
    void* lib = nullptr;
    int (*init)() = nullptr;
    void (*terminate)() = nullptr;
    int (*getError)(const char**) = nullptr;
    void (*defaultHints)() = nullptr;
    void (*hint)(int, int) = nullptr;
    GLFWwindow* (*create)(int, int, const char*, GLFWmonitor*, GLFWwindow*) = nullptr;
    void (*destroy)(GLFWwindow*) = nullptr;
    int (*vulkanSupported)() = nullptr;
    void (*poll)() = nullptr;
    void (*waitTimeout)(double) = nullptr;
    int (*getAttrib)(GLFWwindow*, int) = nullptr;
    int (*shouldClose)(GLFWwindow*) = nullptr;
    void (*setSize)(GLFWwindow*, int, int) = nullptr;
    void (*getFramebufferSize)(GLFWwindow*, int*, int*) = nullptr;
    void (*show)(GLFWwindow*) = nullptr;
    void (*getCursorPos)(GLFWwindow*, double*, double*) = nullptr;
    int (*getMouseButton)(GLFWwindow*, int) = nullptr;
    int (*getKey)(GLFWwindow*, int) = nullptr;
    void (*getWindowSize)(GLFWwindow*, int*, int*) = nullptr;
    void (*setUserPointer)(GLFWwindow*, void*) = nullptr;
    void* (*getUserPointer)(GLFWwindow*) = nullptr;
    GLFWscrollfun (*setScrollCallback)(GLFWwindow*, GLFWscrollfun) = nullptr;
    GLFWcharfun (*setCharCallback)(GLFWwindow*, GLFWcharfun) = nullptr;
    GLFWkeyfun (*setKeyCallback)(GLFWwindow*, GLFWkeyfun) = nullptr;
    GLFWdropfun (*setDropCallback)(GLFWwindow*, GLFWdropfun) = nullptr;
};

// gdi::Key's GLFW key codes, in its order.
const int kGlfwKeys[size_t(gdi::Key::Count)] = {GLFW_KEY_W,
                                                GLFW_KEY_A,
                                                GLFW_KEY_S,
                                                GLFW_KEY_D,
                                                GLFW_KEY_Q,
                                                GLFW_KEY_E,
                                                GLFW_KEY_R,
                                                GLFW_KEY_F,
                                                GLFW_KEY_P,
                                                GLFW_KEY_SPACE,
                                                GLFW_KEY_ESCAPE,
                                                GLFW_KEY_TAB,
                                                GLFW_KEY_ENTER,
                                                GLFW_KEY_BACKSPACE,
                                                GLFW_KEY_DELETE,
                                                GLFW_KEY_LEFT,
                                                GLFW_KEY_RIGHT,
                                                GLFW_KEY_UP,
                                                GLFW_KEY_DOWN,
                                                GLFW_KEY_HOME,
                                                GLFW_KEY_END,
                                                GLFW_KEY_LEFT_SHIFT,
                                                GLFW_KEY_LEFT_CONTROL,
                                                GLFW_KEY_F1,
                                                GLFW_KEY_F2,
                                                GLFW_KEY_F12};

const Glfw& glfw() {
    static Glfw g;
    if (g.lib) return g;
    static const char* const names[] = {"libglfw.so.3", "libglfw.so", nullptr};
    Glfw t;
    t.lib = openLibrary(names, "libglfw3");
    t.init = symbol<decltype(t.init)>(t.lib, "glfwInit");
    t.terminate = symbol<decltype(t.terminate)>(t.lib, "glfwTerminate");
    t.getError = symbol<decltype(t.getError)>(t.lib, "glfwGetError");
    t.defaultHints = symbol<decltype(t.defaultHints)>(t.lib, "glfwDefaultWindowHints");
    t.hint = symbol<decltype(t.hint)>(t.lib, "glfwWindowHint");
    t.create = symbol<decltype(t.create)>(t.lib, "glfwCreateWindow");
    t.destroy = symbol<decltype(t.destroy)>(t.lib, "glfwDestroyWindow");
    t.vulkanSupported = symbol<decltype(t.vulkanSupported)>(t.lib, "glfwVulkanSupported");
    t.poll = symbol<decltype(t.poll)>(t.lib, "glfwPollEvents");
    t.waitTimeout = symbol<decltype(t.waitTimeout)>(t.lib, "glfwWaitEventsTimeout");
    t.getAttrib = symbol<decltype(t.getAttrib)>(t.lib, "glfwGetWindowAttrib");
    t.shouldClose = symbol<decltype(t.shouldClose)>(t.lib, "glfwWindowShouldClose");
    t.setSize = symbol<decltype(t.setSize)>(t.lib, "glfwSetWindowSize");
    t.getFramebufferSize = symbol<decltype(t.getFramebufferSize)>(t.lib, "glfwGetFramebufferSize");
    t.show = symbol<decltype(t.show)>(t.lib, "glfwShowWindow");
    t.getCursorPos = symbol<decltype(t.getCursorPos)>(t.lib, "glfwGetCursorPos");
    t.getMouseButton = symbol<decltype(t.getMouseButton)>(t.lib, "glfwGetMouseButton");
    t.getKey = symbol<decltype(t.getKey)>(t.lib, "glfwGetKey");
    t.getWindowSize = symbol<decltype(t.getWindowSize)>(t.lib, "glfwGetWindowSize");
    t.setUserPointer = symbol<decltype(t.setUserPointer)>(t.lib, "glfwSetWindowUserPointer");
    t.getUserPointer = symbol<decltype(t.getUserPointer)>(t.lib, "glfwGetWindowUserPointer");
    t.setScrollCallback = symbol<decltype(t.setScrollCallback)>(t.lib, "glfwSetScrollCallback");
    t.setCharCallback = symbol<decltype(t.setCharCallback)>(t.lib, "glfwSetCharCallback");
    t.setKeyCallback = symbol<decltype(t.setKeyCallback)>(t.lib, "glfwSetKeyCallback");
    t.setDropCallback = symbol<decltype(t.setDropCallback)>(t.lib, "glfwSetDropCallback");
    g = t;
    return g;
}

// glfwInit/glfwTerminate are process-wide: terminate with the last window, of either API.
int liveWindows = 0;

gdi::Error glfwError(const Glfw& g, const std::string& what) {
    const char* text = nullptr;
    g.getError(&text);
    return gdi::Error("GLFW: " + what + (text ? std::string(": ") + text : std::string()));
}

}  // namespace

GlfwWindow::GlfwWindow(Api api, bool debug) {
    const char* x11 = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!x11 || !*x11) && (!wayland || !*wayland))
        throw gdi::Error(
            "GLFW: no display (DISPLAY and WAYLAND_DISPLAY are unset; run under a desktop or xvfb-run)");
    const Glfw& g = glfw();
    lib_ = g.lib;
    if (!g.init()) throw glfwError(g, "glfwInit failed");
    initialised_ = true;
    ++liveWindows;
    try {
        g.defaultHints();
        g.hint(GLFW_VISIBLE,
               GLFW_FALSE);  // shown on the first present; offscreen work needs no window
        if (api == Api::Vulkan) {
            // GLFW finds the Vulkan loader itself; without it no surface can be made.
            if (!g.vulkanSupported())
                throw glfwError(
                    g, "no Vulkan loader for window surfaces (apt-get install libvulkan1)");
            g.hint(GLFW_CLIENT_API, GLFW_NO_API);
        } else {
            g.hint(GLFW_CONTEXT_VERSION_MAJOR, 4);
            g.hint(GLFW_CONTEXT_VERSION_MINOR, 5);
            g.hint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
            g.hint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
            g.hint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
            g.hint(GLFW_SRGB_CAPABLE, GLFW_TRUE);
            // Robust first, as on EGL (resets are reported); a plain context where the driver refuses.
            g.hint(GLFW_CONTEXT_ROBUSTNESS, GLFW_LOSE_CONTEXT_ON_RESET);
        }
        window_ = g.create(320, 240, "fe", nullptr, nullptr);
        if (!window_ && api == Api::OpenGL45) {
            g.hint(GLFW_CONTEXT_ROBUSTNESS, GLFW_NO_ROBUSTNESS);
            window_ = g.create(320, 240, "fe", nullptr, nullptr);
        }
        if (!window_)
            throw glfwError(g, api == Api::Vulkan
                                   ? "cannot create a window"
                                   : "cannot create a window with an OpenGL 4.5 core context");
        // The wheel and typed text arrive as events: gathered here until the next poll().
        auto* window = static_cast<GLFWwindow*>(window_);
        g.setUserPointer(window, this);
        g.setScrollCallback(window, [](GLFWwindow* w, double, double dy) {
            static_cast<GlfwWindow*>(glfw().getUserPointer(w))->wheel_ += float(dy);
        });
        // Presses are counted as they happen, so a tap between two polls is not lost.
        g.setKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int) {
            if (action != GLFW_PRESS) return;
            auto* self = static_cast<GlfwWindow*>(glfw().getUserPointer(w));
            for (size_t k = 0; k < size_t(gdi::Key::Count); ++k)
                if (kGlfwKeys[k] == key && self->presses_[k] < 255) ++self->presses_[k];
        });
        g.setDropCallback(window, [](GLFWwindow* w, int count, const char** paths) {
            auto* self = static_cast<GlfwWindow*>(glfw().getUserPointer(w));
            for (int i = 0; i < count; ++i) self->dropped_.emplace_back(paths[i]);
        });
        g.setCharCallback(window, [](GLFWwindow* w, unsigned int c) {
            std::string& text = static_cast<GlfwWindow*>(glfw().getUserPointer(w))->text_;
            if (c < 0x80)
                text += char(c);  // UTF-8 encoding of one code point
            else if (c < 0x800)
                text += char(0xC0 | (c >> 6)), text += char(0x80 | (c & 0x3F));
            else if (c < 0x10000)
                text += char(0xE0 | (c >> 12)), text += char(0x80 | ((c >> 6) & 0x3F)),
                    text += char(0x80 | (c & 0x3F));
            else
                text += char(0xF0 | (c >> 18)), text += char(0x80 | ((c >> 12) & 0x3F)),
                    text += char(0x80 | ((c >> 6) & 0x3F)), text += char(0x80 | (c & 0x3F));
        });
    } catch (...) {
        release();  // the destructor does not run when the constructor throws
        throw;
    }
}

GlfwWindow::~GlfwWindow() { release(); }

void GlfwWindow::release() {
    const Glfw& g = glfw();
    if (window_) g.destroy(static_cast<GLFWwindow*>(window_)), window_ = nullptr;
    if (initialised_ && --liveWindows == 0) g.terminate();
    initialised_ = false;
}

void* GlfwWindow::symbol(const char* name) const { return librarySymbol(lib_, name); }

GlfwWindow::Size GlfwWindow::framebufferSize() const {
    int w = 0, h = 0;
    glfw().getFramebufferSize(static_cast<GLFWwindow*>(window_), &w, &h);
    return {uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))};
}

GlfwWindow::Size GlfwWindow::prepare(uint32_t width, uint32_t height, bool* firstShow) {
    const Glfw& g = glfw();
    auto* window = static_cast<GLFWwindow*>(window_);
    Size size = framebufferSize();
    const bool resize = size.width != width || size.height != height;
    if (resize) g.setSize(window, int(width), int(height));
    if (firstShow) *firstShow = !shown_;
    if (!shown_) {
        g.show(window), shown_ = true;
        // Pixels sent to a window the server has not mapped yet are lost: wait (up to 1 s)
        // until GLFW reports it viewable.
        for (int i = 0; i < 100 && !g.getAttrib(window, GLFW_VISIBLE); ++i) g.waitTimeout(0.01);
    }
    // The window system applies a resize asynchronously: wait (up to 1 s) for it, so the frame
    // is not drawn for the old size. A window manager may still refuse the size.
    for (int i = 0; i < 100; ++i) {
        if (resize)
            g.waitTimeout(0.01);
        else
            g.poll();
        size = framebufferSize();
        if (!resize || (size.width == width && size.height == height)) break;
    }
    return size;
}

bool GlfwWindow::poll() {
    const Glfw& g = glfw();
    g.poll();
    auto* window = static_cast<GLFWwindow*>(window_);
    gdi::InputState in;
    double x = 0, y = 0;
    g.getCursorPos(window, &x, &y);
    // Cursor positions are in screen coordinates: scaled to framebuffer pixels (HiDPI).
    int ww = 0, wh = 0;
    g.getWindowSize(window, &ww, &wh);
    const Size fb = framebufferSize();
    in.mouseX = float(x * (ww > 0 ? double(fb.width) / ww : 1.0));
    in.mouseY = float(y * (wh > 0 ? double(fb.height) / wh : 1.0));
    for (int b = 0; b < 3; ++b) in.mouse[b] = g.getMouseButton(window, b) == GLFW_PRESS;
    for (size_t k = 0; k < size_t(gdi::Key::Count); ++k)
        in.keys[k] = g.getKey(window, kGlfwKeys[k]) == GLFW_PRESS;
    std::copy(std::begin(presses_), std::end(presses_), std::begin(in.presses));
    std::fill(std::begin(presses_), std::end(presses_), uint8_t(0));
    in.droppedFiles = std::move(dropped_);
    dropped_.clear();
    in.wheel = wheel_;
    in.text = std::move(text_);
    wheel_ = 0;
    text_.clear();
    input_ = std::move(in);
    return !g.shouldClose(window);
}

gdi::Image GlfwWindow::read(uint32_t width, uint32_t height) const {
    if (width == 0 || height == 0) throw gdi::Error("readWindow: nothing presented yet");
    // Present only in an X11 build of GLFW, and null when the window is not an X11 one.
    auto getDisplay = reinterpret_cast<Display* (*)()>(dlsym(lib_, "glfwGetX11Display"));
    auto getWindow = reinterpret_cast<Window (*)(GLFWwindow*)>(dlsym(lib_, "glfwGetX11Window"));
    Display* display = getDisplay && getWindow ? getDisplay() : nullptr;
    if (!display)
        throw gdi::Error("GLFW: reading the window back needs X11 (this is not an X11 window)");
    static const char* const names[] = {"libX11.so.6", "libX11.so", nullptr};
    void* x11 = openLibrary(names, "libx11-6");  // already loaded by GLFW: this only finds it
    auto sync = platform::symbol<int (*)(Display*, Bool)>(x11, "XSync");
    auto getImage = platform::symbol<XImage* (*)(Display*, Drawable, int, int, unsigned, unsigned,
                                                 unsigned long, int)>(x11, "XGetImage");
    auto setHandler = platform::symbol<XErrorHandler (*)(XErrorHandler)>(x11, "XSetErrorHandler");
    // The server has handled every request sent so far (GL swaps, and the Vulkan WSI's
    // images, which Mesa sends on this same connection).
    sync(display, False);
    // Xlib's default handler exits the process on BadMatch (window not fully on screen).
    XErrorHandler old = setHandler([](Display*, XErrorEvent*) { return 0; });
    XImage* image = getImage(display, getWindow(static_cast<GLFWwindow*>(window_)), 0, 0, width,
                             height, AllPlanes, ZPixmap);
    sync(display, False);
    setHandler(old);
    if (!image) throw gdi::Error("GLFW: XGetImage failed (is the window fully on screen?)");
    auto channel = [](unsigned long pixel, unsigned long mask) {
        int shift = 0;
        while (mask && !(mask & 1)) mask >>= 1, ++shift;
        return uint8_t(mask ? ((pixel >> shift) & mask) * 255 / mask : 0);
    };
    std::vector<uint8_t> rgba;
    rgba.reserve(size_t(width) * height * 4);
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) {
            unsigned long p = image->f.get_pixel(image, int(x), int(y));
            for (uint8_t v : {channel(p, image->red_mask), channel(p, image->green_mask),
                              channel(p, image->blue_mask), uint8_t(255)})
                rgba.push_back(v);
        }
    image->f.destroy_image(image);
    return gdi::Image{width, height, gdi::Format::RGBA8, std::move(rgba)};
}

}  // namespace fe::platform
