#include "gl/GlPlatform.h"

#include <dlfcn.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>

#include "fe/gdi/Device.h"

namespace fe::gl {

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
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
        context_ = createContext(display_, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
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

}  // namespace

std::unique_ptr<GlPlatform> createPlatform(PlatformKind kind, bool debug) {
    switch (kind) {
        case PlatformKind::Egl: return std::make_unique<EglPlatform>(debug);
        case PlatformKind::OSMesa: return std::make_unique<OsmesaPlatform>(debug);
        default: throw gdi::Error("gl-glfw: windowed GL through GLFW is not built in this version");
    }
}

}  // namespace fe::gl
