// Where a GL context comes from, apart from the driver (Filament's Platform idea): EGL
// (surfaceless, headless), OSMesa (offscreen), GLFW (a window, X11 or Wayland).
// Libraries are opened at run time so a missing one is a reason, not a link failure.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gl/GlBackend.h"

namespace fe::gl {

class GlPlatform {
public:
    virtual ~GlPlatform() = default;
    virtual const char* name() const = 0;
    virtual void* getProcAddress(const char* name) = 0;
    // Binds the context to the calling thread / unbinds it from the calling thread (a context
    // is current on one thread at a time; the device moves it to its context thread).
    virtual void makeCurrent() = 0;
    virtual void releaseCurrent() = 0;

    // Window platforms only (GLFW); headless ones keep these defaults.
    virtual bool hasWindow() const { return false; }
    // How swapped frames reach the screen (DeviceInfo::presentMode).
    virtual std::string presentMode() const { return ""; }
    // Sizes the window to width x height (first call also shows it) before a frame is drawn to
    // it; returns the framebuffer size the window really has (a window manager may refuse).
    // Window calls: on the thread that made the platform.
    virtual std::pair<uint32_t, uint32_t> prepareWindow(uint32_t width, uint32_t height) {
        return {0, 0};
    }
    // Where the context is current: before a frame is drawn to the window, and the swap.
    virtual void beforeDraw() {}
    virtual void swap() {}
    // Handles the window's events; false once the user has closed it. Window calls' thread.
    virtual bool poll() { return false; }
    // What the window shows on screen, width x height from its top-left, RGBA8 rows top-down,
    // read back from the window system (X11), not from GL.
    virtual gdi::Image readWindow(uint32_t width, uint32_t height);
    // The window's input as of the last swapAndPoll() (none without a window).
    virtual gdi::InputState input() const { return {}; }
};

// Creates a 4.5 core context (debug context when `debug`); throws gdi::Error saying why not.
// `vsync`: window platforms swap on the display's refresh (swap interval 1) or at once (0).
std::unique_ptr<GlPlatform> createPlatform(PlatformKind kind, bool debug, bool vsync = true);

}  // namespace fe::gl
