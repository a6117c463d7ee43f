#include "gl/GlPlatform.h"

#include <dlfcn.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <X11/Xlib.h>  // after Device.h: Xlib defines macros such as None

#include <algorithm>
#include <cstdlib>

#include "fe/gdi/Device.h"

namespace fe::gl {

std::vector<uint8_t> GlPlatform::readWindow(uint32_t, uint32_t) {
    throw gdi::Error(std::string(name()) + ": no window to read");
}

namespace {

void* openLibrary(const char* const* names, const char* package) {
    for (const char* const* n = names; *n; ++n)
        if (void* h = dlopen(*n, RTLD_NOW | RTLD_LOCAL)) return h;
    throw gdi::Error(std::string(names[0]) + " not found (apt-get install " + package + ")");
}

template <class T>
T symbol(void* lib, const char* name) {
    void* p = dlsym(lib, name);
    if (!p) throw gdi::Error(std::string("symbol ") + name + " missing from its library");
    return reinterpret_cast<T>(p);
}

class EglPlatform final : public GlPlatform {
public:
    explicit EglPlatform(bool debug) {
        static const char* const names[] = {"libEGL.so.1", "libEGL.so", nullptr};
        lib_ = openLibrary(names, "libegl1");
        getProc_ = symbol<PFNEGLGETPROCADDRESSPROC>(lib_, "eglGetProcAddress");
        auto initialize = symbol<PFNEGLINITIALIZEPROC>(lib_, "eglInitialize");
        auto bindApi = symbol<PFNEGLBINDAPIPROC>(lib_, "eglBindAPI");
        auto createContext = symbol<PFNEGLCREATECONTEXTPROC>(lib_, "eglCreateContext");
        makeCurrent_ = symbol<PFNEGLMAKECURRENTPROC>(lib_, "eglMakeCurrent");
        destroyContext_ = symbol<PFNEGLDESTROYCONTEXTPROC>(lib_, "eglDestroyContext");
        terminate_ = symbol<PFNEGLTERMINATEPROC>(lib_, "eglTerminate");
        auto getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(getProc_("eglGetPlatformDisplayEXT"));
        if (!getPlatformDisplay) throw gdi::Error("EGL: eglGetPlatformDisplayEXT unavailable");
        display_ = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        EGLint major = 0, minor = 0;
        if (display_ == EGL_NO_DISPLAY || !initialize(display_, &major, &minor))
            throw gdi::Error("EGL: no surfaceless display (Mesa EGL_MESA_platform_surfaceless required)");
        if (!bindApi(EGL_OPENGL_API)) throw gdi::Error("EGL: desktop OpenGL API unavailable");
        // Robust first (EGL 1.5 / KHR_create_context): a GPU reset is then reported through
        // glGetGraphicsResetStatus and the device becomes lost instead of undefined. Drivers
        // without robustness refuse it: a plain context then.
        const EGLint robust[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                 EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE,
                                 EGL_CONTEXT_OPENGL_ROBUST_ACCESS, EGL_TRUE,
                                 EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY, EGL_LOSE_CONTEXT_ON_RESET, EGL_NONE};
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
        context_ = createContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, robust);
        if (context_ == EGL_NO_CONTEXT) context_ = createContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
        if (context_ == EGL_NO_CONTEXT) throw gdi::Error("EGL: cannot create an OpenGL 4.5 core context");
        makeCurrent();
    }
    ~EglPlatform() override {
        if (context_ != EGL_NO_CONTEXT) {
            makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            destroyContext_(display_, context_);
        }
        if (display_ != EGL_NO_DISPLAY) terminate_(display_);
    }
    const char* name() const override { return "gl-egl"; }
    void* getProcAddress(const char* n) override { return reinterpret_cast<void*>(getProc_(n)); }
    void makeCurrent() override {
        if (!makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw gdi::Error("EGL: eglMakeCurrent failed");
    }

private:
    void* lib_ = nullptr;
    PFNEGLGETPROCADDRESSPROC getProc_ = nullptr;
    PFNEGLMAKECURRENTPROC makeCurrent_ = nullptr;
    PFNEGLDESTROYCONTEXTPROC destroyContext_ = nullptr;
    PFNEGLTERMINATEPROC terminate_ = nullptr;
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

class OsmesaPlatform final : public GlPlatform {
    using CreateFn = OSMesaContext (*)(const int*, OSMesaContext);
    using MakeCurrentFn = GLboolean (*)(OSMesaContext, void*, GLenum, GLsizei, GLsizei);
    using GetProcFn = OSMESAproc (*)(const char*);
    using DestroyFn = void (*)(OSMesaContext);

public:
    explicit OsmesaPlatform(bool) {
        static const char* const names[] = {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so", nullptr};
        lib_ = openLibrary(names, "libosmesa6");
        auto create = symbol<CreateFn>(lib_, "OSMesaCreateContextAttribs");
        makeCurrent_ = symbol<MakeCurrentFn>(lib_, "OSMesaMakeCurrent");
        getProc_ = symbol<GetProcFn>(lib_, "OSMesaGetProcAddress");
        destroy_ = symbol<DestroyFn>(lib_, "OSMesaDestroyContext");
        const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION, 4, OSMESA_CONTEXT_MINOR_VERSION, 5, 0};
        context_ = create(attribs, nullptr);
        if (!context_) throw gdi::Error("OSMesa: cannot create an OpenGL 4.5 core context");
        makeCurrent();
    }
    ~OsmesaPlatform() override {
        if (context_) destroy_(context_);
    }
    const char* name() const override { return "gl-osmesa"; }
    void* getProcAddress(const char* n) override { return reinterpret_cast<void*>(getProc_(n)); }
    void makeCurrent() override {
        // OSMesa needs a colour buffer to be current; all rendering goes to framebuffer objects.
        if (!makeCurrent_(context_, buffer_, GL_UNSIGNED_BYTE, 4, 4)) throw gdi::Error("OSMesa: OSMesaMakeCurrent failed");
    }

private:
    void* lib_ = nullptr;
    MakeCurrentFn makeCurrent_ = nullptr;
    GetProcFn getProc_ = nullptr;
    DestroyFn destroy_ = nullptr;
    OSMesaContext context_ = nullptr;
    unsigned char buffer_[4 * 4 * 4] = {};
};

// A GLFW window owns the context. The library is opened at run time like the others, so a
// machine without libglfw3 or without a display still runs the headless backends.
class GlfwPlatform final : public GlPlatform {
public:
    explicit GlfwPlatform(bool debug) {
        const char* x11 = std::getenv("DISPLAY");
        const char* wayland = std::getenv("WAYLAND_DISPLAY");
        if ((!x11 || !*x11) && (!wayland || !*wayland))
            throw gdi::Error("GLFW: no display (DISPLAY and WAYLAND_DISPLAY are unset; run under a desktop or xvfb-run)");
        static const char* const names[] = {"libglfw.so.3", "libglfw.so", nullptr};
        lib_ = openLibrary(names, "libglfw3");
        auto init = symbol<int (*)()>(lib_, "glfwInit");
        auto getError = symbol<int (*)(const char**)>(lib_, "glfwGetError");
        auto hint = symbol<void (*)(int, int)>(lib_, "glfwWindowHint");
        auto defaultHints = symbol<void (*)()>(lib_, "glfwDefaultWindowHints");
        auto create = symbol<GLFWwindow* (*)(int, int, const char*, GLFWmonitor*, GLFWwindow*)>(lib_, "glfwCreateWindow");
        terminate_ = symbol<void (*)()>(lib_, "glfwTerminate");
        destroyWindow_ = symbol<void (*)(GLFWwindow*)>(lib_, "glfwDestroyWindow");
        makeCurrent_ = symbol<void (*)(GLFWwindow*)>(lib_, "glfwMakeContextCurrent");
        getProc_ = symbol<GLFWglproc (*)(const char*)>(lib_, "glfwGetProcAddress");
        swap_ = symbol<void (*)(GLFWwindow*)>(lib_, "glfwSwapBuffers");
        poll_ = symbol<void (*)()>(lib_, "glfwPollEvents");
        waitTimeout_ = symbol<void (*)(double)>(lib_, "glfwWaitEventsTimeout");
        getAttrib_ = symbol<int (*)(GLFWwindow*, int)>(lib_, "glfwGetWindowAttrib");
        shouldClose_ = symbol<int (*)(GLFWwindow*)>(lib_, "glfwWindowShouldClose");
        setSize_ = symbol<void (*)(GLFWwindow*, int, int)>(lib_, "glfwSetWindowSize");
        getFramebufferSize_ = symbol<void (*)(GLFWwindow*, int*, int*)>(lib_, "glfwGetFramebufferSize");
        show_ = symbol<void (*)(GLFWwindow*)>(lib_, "glfwShowWindow");
        auto why = [&](const char* what) {
            const char* text = nullptr;
            getError(&text);
            return gdi::Error(std::string("GLFW: ") + what + (text ? std::string(": ") + text : std::string()));
        };
        if (!init()) throw why("glfwInit failed");
        ++liveWindows();
        defaultHints();
        hint(GLFW_VISIBLE, GLFW_FALSE);  // shown on the first present; offscreen work needs no window
        hint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        hint(GLFW_CONTEXT_VERSION_MINOR, 5);
        hint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        hint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        hint(GLFW_OPENGL_DEBUG_CONTEXT, debug ? GLFW_TRUE : GLFW_FALSE);
        hint(GLFW_SRGB_CAPABLE, GLFW_TRUE);
        // Robust first, as on EGL (resets reported); a plain context where the driver refuses.
        hint(GLFW_CONTEXT_ROBUSTNESS, GLFW_LOSE_CONTEXT_ON_RESET);
        window_ = create(320, 240, "fe", nullptr, nullptr);
        if (!window_) {
            hint(GLFW_CONTEXT_ROBUSTNESS, GLFW_NO_ROBUSTNESS);
            window_ = create(320, 240, "fe", nullptr, nullptr);
        }
        if (!window_) {
            gdi::Error e = why("cannot create a window with an OpenGL 4.5 core context");
            release();
            throw e;
        }
        makeCurrent();
    }
    ~GlfwPlatform() override { release(); }
    const char* name() const override { return "gl-glfw"; }
    void* getProcAddress(const char* n) override { return reinterpret_cast<void*>(getProc_(n)); }
    void makeCurrent() override { makeCurrent_(window_); }
    bool hasWindow() const override { return true; }
    std::pair<uint32_t, uint32_t> prepareWindow(uint32_t width, uint32_t height) override {
        int w = 0, h = 0;
        getFramebufferSize_(window_, &w, &h);
        const bool resize = uint32_t(w) != width || uint32_t(h) != height;
        if (resize) setSize_(window_, int(width), int(height));
        if (!shown_) {
            show_(window_), shown_ = true;
            // A swap to a window the server has not mapped yet is lost: wait (up to 1 s) until
            // GLFW reports it viewable.
            for (int i = 0; i < 100 && !getAttrib_(window_, GLFW_VISIBLE); ++i) waitTimeout_(0.01);
            // Mesa's software GLX drops the first frame swapped to a newly mapped window; an
            // empty swap first makes the first real frame appear.
            swap_(window_);
        }
        // The window system applies a resize asynchronously: wait (up to 1 s) for it, so the
        // frame is not drawn for the old size. A window manager may still refuse the size.
        for (int i = 0; i < 100; ++i) {
            if (resize) waitTimeout_(0.01);
            else poll_();
            getFramebufferSize_(window_, &w, &h);
            if (!resize || (uint32_t(w) == width && uint32_t(h) == height)) break;
        }
        return {uint32_t(std::max(w, 0)), uint32_t(std::max(h, 0))};
    }
    bool swapAndPoll() override {
        swap_(window_);
        poll_();
        return !shouldClose_(window_);
    }

    std::vector<uint8_t> readWindow(uint32_t width, uint32_t height) override {
        auto getDisplay = reinterpret_cast<Display* (*)()>(dlsym(lib_, "glfwGetX11Display"));
        auto getWindow = reinterpret_cast<Window (*)(GLFWwindow*)>(dlsym(lib_, "glfwGetX11Window"));
        Display* display = getDisplay ? getDisplay() : nullptr;
        if (!display) throw gdi::Error("GLFW: reading the window back needs X11 (this is not an X11 window)");
        static const char* const names[] = {"libX11.so.6", "libX11.so", nullptr};
        void* x11 = openLibrary(names, "libx11-6");
        auto sync = symbol<int (*)(Display*, Bool)>(x11, "XSync");
        auto getImage = symbol<XImage* (*)(Display*, Drawable, int, int, unsigned, unsigned, unsigned long, int)>(x11, "XGetImage");
        auto setHandler = symbol<XErrorHandler (*)(XErrorHandler)>(x11, "XSetErrorHandler");
        sync(display, False);  // the server has drawn every swap sent so far
        // Xlib's default handler exits the process on BadMatch (window not fully on screen).
        XErrorHandler old = setHandler([](Display*, XErrorEvent*) { return 0; });
        XImage* image = getImage(display, getWindow(window_), 0, 0, width, height, AllPlanes, ZPixmap);
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
                for (uint8_t v : {channel(p, image->red_mask), channel(p, image->green_mask), channel(p, image->blue_mask), uint8_t(255)})
                    rgba.push_back(v);
            }
        image->f.destroy_image(image);
        return rgba;
    }

private:
    // glfwInit/glfwTerminate are process-wide: terminate with the last window.
    static int& liveWindows() {
        static int n = 0;
        return n;
    }
    void release() {
        if (window_) destroyWindow_(window_), window_ = nullptr;
        if (terminate_ && liveWindows() > 0 && --liveWindows() == 0) terminate_();
        terminate_ = nullptr;
    }
    void* lib_ = nullptr;
    GLFWwindow* window_ = nullptr;
    bool shown_ = false;
    void (*terminate_)() = nullptr;
    void (*destroyWindow_)(GLFWwindow*) = nullptr;
    void (*makeCurrent_)(GLFWwindow*) = nullptr;
    GLFWglproc (*getProc_)(const char*) = nullptr;
    void (*swap_)(GLFWwindow*) = nullptr;
    void (*poll_)() = nullptr;
    void (*waitTimeout_)(double) = nullptr;
    int (*getAttrib_)(GLFWwindow*, int) = nullptr;
    int (*shouldClose_)(GLFWwindow*) = nullptr;
    void (*setSize_)(GLFWwindow*, int, int) = nullptr;
    void (*getFramebufferSize_)(GLFWwindow*, int*, int*) = nullptr;
    void (*show_)(GLFWwindow*) = nullptr;
};

}  // namespace

std::unique_ptr<GlPlatform> createPlatform(PlatformKind kind, bool debug) {
    switch (kind) {
        case PlatformKind::Egl: return std::make_unique<EglPlatform>(debug);
        case PlatformKind::OSMesa: return std::make_unique<OsmesaPlatform>(debug);
        case PlatformKind::Glfw: return std::make_unique<GlfwPlatform>(debug);
    }
    throw gdi::Error("unknown GL platform");
}

}  // namespace fe::gl
