#include "gl/GlPlatform.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <utility>
#include <cstdlib>

#include "fe/gdi/Device.h"
#include "platform/DynamicLibrary.h"
#include "platform/GlfwWindow.h"

namespace fe::gl {

gdi::Image GlPlatform::readWindow(uint32_t, uint32_t) {
    throw gdi::Error(std::string(name()) + ": no window to read");
}

namespace {

using platform::openLibrary;
using platform::symbol;

// Every device in the process gets the same surfaceless EGLDisplay, and eglTerminate is not
// counted: one device's terminate while another device was being made on another thread failed
// the other's eglMakeCurrent (ExecutionModel.DevicesComeAndGoWhileAnotherWorks). So the display
// is initialized and terminated by count: the last device to go terminates it.
std::mutex& eglDisplayMutex() {
    static std::mutex m;
    return m;
}
uint32_t eglDisplayUsers = 0;  // guarded by eglDisplayMutex()

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
        {
            const std::lock_guard lock(eglDisplayMutex());
            if (display_ == EGL_NO_DISPLAY || !initialize(display_, &major, &minor)) {
                display_ = EGL_NO_DISPLAY;  // not ours to terminate
                throw gdi::Error(
                    "EGL: no surfaceless display (Mesa EGL_MESA_platform_surfaceless required)");
            }
            ++eglDisplayUsers;
        }
        try {
            if (!bindApi(EGL_OPENGL_API)) throw gdi::Error("EGL: desktop OpenGL API unavailable");
            // Robust first (EGL 1.5 / KHR_create_context): a GPU reset is then reported through
            // glGetGraphicsResetStatus and the device becomes lost instead of undefined. Drivers
            // without robustness refuse it: a plain context then.
            const EGLint robust[] = {EGL_CONTEXT_MAJOR_VERSION,
                                     4,
                                     EGL_CONTEXT_MINOR_VERSION,
                                     5,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                     EGL_CONTEXT_OPENGL_DEBUG,
                                     debug ? EGL_TRUE : EGL_FALSE,
                                     EGL_CONTEXT_OPENGL_ROBUST_ACCESS,
                                     EGL_TRUE,
                                     EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY,
                                     EGL_LOSE_CONTEXT_ON_RESET,
                                     EGL_NONE};
            const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      4,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_CONTEXT_OPENGL_DEBUG,
                                      debug ? EGL_TRUE : EGL_FALSE,
                                      EGL_NONE};
            context_ = createContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, robust);
            if (context_ == EGL_NO_CONTEXT)
                context_ = createContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
            if (context_ == EGL_NO_CONTEXT)
                throw gdi::Error("EGL: cannot create an OpenGL 4.5 core context");
            makeCurrent();
        } catch (...) {
            release();  // the destructor does not run when the constructor throws
            throw;
        }
    }
    ~EglPlatform() override { release(); }
    const char* name() const override { return "gl-egl"; }
    void* getProcAddress(const char* n) override { return reinterpret_cast<void*>(getProc_(n)); }
    void makeCurrent() override {
        if (!makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw gdi::Error("EGL: eglMakeCurrent failed");
    }
    void releaseCurrent() override {
        makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }

private:
    void release() {
        if (context_ != EGL_NO_CONTEXT) {
            makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            destroyContext_(display_, std::exchange(context_, EGL_NO_CONTEXT));
        }
        if (display_ == EGL_NO_DISPLAY) return;
        const std::lock_guard lock(eglDisplayMutex());
        if (--eglDisplayUsers == 0) terminate_(std::exchange(display_, EGL_NO_DISPLAY));
        display_ = EGL_NO_DISPLAY;
    }
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
        static const char* const names[] = {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so",
                                            nullptr};
        lib_ = openLibrary(names, "libosmesa6");
        auto create = symbol<CreateFn>(lib_, "OSMesaCreateContextAttribs");
        makeCurrent_ = symbol<MakeCurrentFn>(lib_, "OSMesaMakeCurrent");
        getProc_ = symbol<GetProcFn>(lib_, "OSMesaGetProcAddress");
        destroy_ = symbol<DestroyFn>(lib_, "OSMesaDestroyContext");
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               5,
                               0};
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
        if (!makeCurrent_(context_, buffer_, GL_UNSIGNED_BYTE, 4, 4))
            throw gdi::Error("OSMesa: OSMesaMakeCurrent failed");
    }
    void releaseCurrent() override {
        makeCurrent_(nullptr, nullptr, 0, 0, 0);
    }  // no context, no buffer: unbind

private:
    void* lib_ = nullptr;
    MakeCurrentFn makeCurrent_ = nullptr;
    GetProcFn getProc_ = nullptr;
    DestroyFn destroy_ = nullptr;
    OSMesaContext context_ = nullptr;
    unsigned char buffer_[4 * 4 * 4] = {};
};

// A GLFW window owns the context; the window itself (library, sizing, read-back) is shared
// with vulkan-glfw (platform/GlfwWindow).
class GlfwPlatform final : public GlPlatform {
public:
    GlfwPlatform(bool debug, bool vsync) : window_(platform::GlfwWindow::Api::OpenGL45, debug) {
        auto* w = static_cast<GLFWwindow*>(window_.handle());
        makeCurrent_ = window_.function<void (*)(GLFWwindow*)>("glfwMakeContextCurrent");
        getProc_ = window_.function<GLFWglproc (*)(const char*)>("glfwGetProcAddress");
        swap_ = window_.function<void (*)(GLFWwindow*)>("glfwSwapBuffers");
        makeCurrent_(w);
        // Swap interval 1 waits for the display's refresh; 0 shows frames as they come.
        window_.function<void (*)(int)>("glfwSwapInterval")(vsync ? 1 : 0);
        presentMode_ = vsync ? "swap interval 1 (vsync on)" : "swap interval 0 (vsync off)";
    }
    const char* name() const override { return "gl-glfw"; }
    void* getProcAddress(const char* n) override { return reinterpret_cast<void*>(getProc_(n)); }
    void makeCurrent() override { makeCurrent_(static_cast<GLFWwindow*>(window_.handle())); }
    void releaseCurrent() override { makeCurrent_(nullptr); }
    bool hasWindow() const override { return true; }
    std::string presentMode() const override { return presentMode_; }
    std::pair<uint32_t, uint32_t> prepareWindow(uint32_t width, uint32_t height) override {
        bool first = false;
        platform::GlfwWindow::Size size = window_.prepare(width, height, &first);
        if (first) emptySwapFirst_ = true;
        return {size.width, size.height};
    }
    // Mesa's software GLX drops the first frame swapped to a newly mapped window; an empty
    // swap first makes the first real frame appear.
    void beforeDraw() override {
        if (std::exchange(emptySwapFirst_, false))
            swap_(static_cast<GLFWwindow*>(window_.handle()));
    }
    void swap() override { swap_(static_cast<GLFWwindow*>(window_.handle())); }
    bool poll() override { return window_.poll(); }
    gdi::Image readWindow(uint32_t width, uint32_t height) override {
        return window_.read(width, height);
    }
    gdi::InputState input() const override { return window_.input(); }

private:
    platform::GlfwWindow window_;
    void (*makeCurrent_)(GLFWwindow*) = nullptr;
    GLFWglproc (*getProc_)(const char*) = nullptr;
    void (*swap_)(GLFWwindow*) = nullptr;
    std::string presentMode_;
    bool emptySwapFirst_ = false;
};

}  // namespace

std::unique_ptr<GlPlatform> createPlatform(PlatformKind kind, bool debug, bool vsync) {
    switch (kind) {
        case PlatformKind::Egl:
            return std::make_unique<EglPlatform>(debug);
        case PlatformKind::OSMesa:
            return std::make_unique<OsmesaPlatform>(debug);
        case PlatformKind::Glfw:
            return std::make_unique<GlfwPlatform>(debug, vsync);
    }
    throw gdi::Error("unknown GL platform");
}

}  // namespace fe::gl
