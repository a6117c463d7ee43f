// RenderDoc in-application capture: one frame written to a .rdc file, opened later in
// qrenderdoc or by tests/renderdoc/inspect_capture.py. librenderdoc.so (Debian: librenderdoc) is
// opened at run time, so a machine without it only loses --capture.
//
//   std::string why;
//   auto rd = platform::RenderDocCapture::load(why);      // BEFORE the device is created
//   if (!rd) fail(why);
//   rd->setCapturePath("out/frame.rdc");
//   auto device = gdi::createDevice(...);
//   rd->startFrame();                                     // before the frame's lists are recorded
//   ... record, submit, wait ...
//   if (rd->endFrame()) print(rd->lastCapturePath());     // out/frame_capture.rdc
//
// Order matters: RenderDoc's Vulkan layer is an implicit layer enabled by an environment
// variable, and the loader reads it in vkCreateInstance; an instance made before load() is never
// captured (startFrame then does nothing and endFrame returns false).
//
// What is captured (RenderDoc 1.24 on Debian 12, lavapipe and llvmpipe, as measured):
//   vulkan, vulkan-glfw: yes, with the library opened here; the Khronos validation layer keeps
//     working and its messages still reach the engine.
//   gl-egl, gl-glfw: only when the process starts with LD_PRELOAD=librenderdoc.so. RenderDoc
//     hooks GL by interposing dlopen/eglGetProcAddress/glXGetProcAddress, which a library opened
//     later cannot do; glHooked() tells which case this is. RenderDoc drops itself from
//     LD_PRELOAD in child processes: put it on the engine's command itself, not on a wrapper
//     (`xvfb-run -a env LD_PRELOAD=librenderdoc.so fe ...`, not `LD_PRELOAD=... xvfb-run ...`).
//   gl-osmesa: never (RenderDoc has no OSMesa hooks).
#pragma once
#include <memory>
#include <string>

struct RENDERDOC_API_1_6_0;  // renderdoc_app.h, kept out of this header

namespace fe::platform {

class RenderDocCapture {
public:
    // The library and its API, or nullptr with a one-line reason in `whyNot` (for instance
    // "librenderdoc.so not found (apt-get install librenderdoc)").
    static std::unique_ptr<RenderDocCapture> load(std::string& whyNot);

    // Where captures go: RenderDoc drops a trailing ".rdc", appends "_capture.rdc" (or
    // "_frameN.rdc"; "_2", "_3"... for more in one run), creates missing folders, and
    // overwrites a file left by an earlier run.
    void setCapturePath(const std::string& pathWithoutOrWithRdc);

    // Captures every API call between the two on the device RenderDoc saw last (there is one).
    // Vulkan: any thread. GL: on the thread the context is current on (GlDevice's
    // runOnContextThread); elsewhere RenderDoc borrows a shared context, which it cannot create
    // on Mesa's surfaceless EGL, and EndFrameCapture crashes.
    void startFrame();
    bool endFrame();  // true when a capture file was written

    // The file RenderDoc wrote for the newest capture of this run; empty when none.
    std::string lastCapturePath() const;

    // Whether RenderDoc sees this process's GL contexts, i.e. librenderdoc was LD_PRELOADed.
    static bool glHooked();

private:
    explicit RenderDocCapture(RENDERDOC_API_1_6_0* api) : api_(api) {}
    RENDERDOC_API_1_6_0* api_;  // RenderDoc's; the library stays loaded until the process ends
};

}  // namespace fe::platform
