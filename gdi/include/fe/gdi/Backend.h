// Layer 4 (GDI isolation): choosing a backend at startup. The only place that knows every backend.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

struct DeviceCreateDesc {
    std::string backend =
        "auto";  // auto | vulkan | gl | gl-egl | gl-osmesa | vulkan-glfw | gl-glfw
    // Khronos validation layer / GL debug context, and the check that one list is used by one
    // thread at a time (ExclusiveUse.h: an Error instead of a corrupted list).
    bool validation = false;
    bool verbose = true;  // auto: say which backend was picked and why others were not
    // A device with a window (Device::present): auto, vulkan and gl stand for their windowed
    // backends (windowCandidates); a headless-only name is an error.
    bool window = false;
    // Windows: frames wait for the display's refresh (Vulkan FIFO, GL swap interval 1); off:
    // Vulkan IMMEDIATE, else MAILBOX, else FIFO (DeviceInfo::presentMode says which), GL 0.
    bool vsync = true;
    // Out-of-range buffer accesses in shaders made safe (DeviceFeatures::robustBufferAccess):
    // a backend that cannot promise it fails to start (auto tries the next). Off by default: it
    // costs time on hardware. gl-egl contexts are robust whenever the driver offers it.
    bool robustBufferAccess = false;
    // A pipeline cache file (Device::openPipelineCache): loaded now, saved when the device goes.
    std::string pipelineCache;
    // A capture file (Capture.h): every call is written there for fe replay and fe bisect,
    // captureFrames frames (0: all) from captureFirstFrame. Empty: FE_CAPTURE, FE_CAPTURE_FRAMES
    // and FE_CAPTURE_FIRST_FRAME from the environment, for the first device the process creates.
    std::string capture;
    uint32_t captureFrames = 0;
    uint32_t captureFirstFrame = 0;  // CaptureDesc::firstFrame; FE_CAPTURE_FIRST_FRAME
};

// Concrete headless backends in the order `auto` tries them (`all` in fe conformance).
const std::vector<std::string>& backendNames();
// Concrete backends with a window, in the order `auto` tries them with a window; `auto`
// without one never picks them.
const std::vector<std::string>& windowBackendNames();
// The windowed backends `name` stands for (auto: vulkan-glfw then gl-glfw; vulkan: vulkan-glfw;
// gl: gl-glfw); empty for a headless-only backend (gl-egl, gl-osmesa). Throws Error for
// unknown names.
std::vector<std::string> windowCandidates(const std::string& name);
// Every accepted --backend value, for error messages.
std::string validBackendList();

struct BackendProbe {
    std::string name;
    bool available = false;
    std::string reason;  // why not, when unavailable
    std::unique_ptr<Device> device;
};

// Starts one named concrete backend; never throws: failure is reported in `reason`.
BackendProbe probeBackend(const std::string& name, bool validation, bool vsync = true,
                          bool robustBufferAccess = false);

// Resolves auto / gl / FE_BACKEND and starts the first backend that works. Throws Error listing
// the valid names for an unknown name, and why each candidate failed when none starts.
std::unique_ptr<Device> createDevice(const DeviceCreateDesc& desc);

// Makes this process's allocator keep the memory it frees (glibc: blocks under 32 MiB from the
// heap, never trimmed, grown 64 MiB at a time) instead of handing it back to the kernel. The CPU
// rasterizers (llvmpipe, lavapipe) allocate and free large blocks every frame; handed back, each
// frame faults their pages in again: 13-15 % of builtin:lights' frame at 1280x720 on a 2-core
// machine (docs/MEASUREMENT_LOG.md). A policy for the whole process, so the application's to
// choose, before it starts a backend (`fe` does, first thing). Nothing where libc is not glibc.
void keepFreedMemory();

// RenderDoc frame captures (RenderDoc's in-application API; Debian's librenderdoc, opened at
// run time). Every object's debugName, each pass's name and each debug group or label reaches
// the capture, which qrenderdoc or python3-renderdoc opens.
//   auto capture = gdi::FrameCapture::load("out/frame");   // BEFORE createDevice
//   auto device = gdi::createDevice({...});
//   capture->begin(*device);  ... record, submit, wait ...  std::string rdc = capture->end(*device);
// Vulkan (vulkan, vulkan-glfw) is captured as is. GL (gl-egl, gl-glfw) only when the process was
// started with LD_PRELOAD=/usr/lib/librenderdoc.so (RenderDoc hooks GL by symbol interposition);
// gl-osmesa never: begin() throws Error saying so.
class FrameCapture {
public:
    // Throws Error with a one-line reason when librenderdoc cannot be loaded. `path`: where the
    // capture goes (RenderDoc writes PATH_capture.rdc, a trailing .rdc dropped).
    static std::unique_ptr<FrameCapture> load(const std::string& path);
    virtual ~FrameCapture() = default;
    // Captures what `device` records and submits from now (lists begun before are not included).
    virtual void begin(Device& device) = 0;
    // Ends the capture after the work submitted so far; returns the .rdc file written.
    virtual std::string end(Device& device) = 0;
};

// Expands "all" into the concrete backends, checks names; throws Error for unknown ones.
std::vector<std::string> expandBackendList(const std::string& nameOrAll);

}  // namespace fe::gdi
