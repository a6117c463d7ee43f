#include "platform/RenderDocCapture.h"

#include <dlfcn.h>
#include <renderdoc_app.h>

#include <cstdlib>
#include <cstring>

#include "fe/gdi/Device.h"
#include "platform/DynamicLibrary.h"

namespace fe::platform {

std::unique_ptr<RenderDocCapture> RenderDocCapture::load(std::string& whyNot) {
    try {
        // Under LD_PRELOAD, or once the Vulkan layer has loaded it, this finds the copy already
        // in the process: there must be one RenderDoc per process.
        static const char* const names[] = {"librenderdoc.so", nullptr};
        void* library = openLibrary(names, "librenderdoc");
        auto getApi = symbol<pRENDERDOC_GetAPI>(library, "RENDERDOC_GetAPI");
        // Everything called here exists since API 1.0.0: the oldest version asks the least of
        // the installed library (later versions only append to the same table).
        RENDERDOC_API_1_0_0* api = nullptr;
        if (!getApi(eRENDERDOC_API_Version_1_0_0, reinterpret_cast<void**>(&api)) || !api)
            throw gdi::Error("librenderdoc.so refused RENDERDOC_GetAPI 1.0.0");
        // The library sets this itself when it starts; set it again so the layer does not
        // depend on that detail. The loader reads it in vkCreateInstance, hence "before the
        // device" (DISABLE_VULKAN_RENDERDOC_CAPTURE_1_24=1 still turns the layer off).
        setenv("ENABLE_VULKAN_RENDERDOC_CAPTURE", "1", 1);
        // RenderDoc mutes the API's debug messages by default, which hides validation errors
        // from the engine's messenger (and tests that expect none would pass unseen).
        api->SetCaptureOptionU32(eRENDERDOC_Option_DebugOutputMute, 0);
        return std::unique_ptr<RenderDocCapture>(new RenderDocCapture(api));
    } catch (const gdi::Error& e) {
        whyNot = e.what();
        return nullptr;
    }
}

void RenderDocCapture::setCapturePath(const std::string& pathWithoutOrWithRdc) {
    api_->SetCaptureFilePathTemplate(pathWithoutOrWithRdc.c_str());
}

namespace {

// RenderDoc's own work when a capture starts and ends (reading resources back, a thumbnail from
// the default framebuffer that a surfaceless GL context lacks) raises API errors that are not the
// engine's: the API's messages are muted just then, and only then.
class MutedApiMessages {
public:
    explicit MutedApiMessages(RENDERDOC_API_1_0_0* api) : api_(api) {
        api_->SetCaptureOptionU32(eRENDERDOC_Option_DebugOutputMute, 1);
    }
    ~MutedApiMessages() { api_->SetCaptureOptionU32(eRENDERDOC_Option_DebugOutputMute, 0); }

private:
    RENDERDOC_API_1_0_0* api_;
};

}  // namespace

// Null device and window: RenderDoc takes the one it saw last, which is ours (one device; a
// headless context has no window to name anyway).
void RenderDocCapture::startFrame() {
    MutedApiMessages muted(api_);
    api_->StartFrameCapture(nullptr, nullptr);
}

bool RenderDocCapture::endFrame() {
    MutedApiMessages muted(api_);
    return api_->EndFrameCapture(nullptr, nullptr) == 1;
}

std::string RenderDocCapture::lastCapturePath() const {
    const uint32_t count = api_->GetNumCaptures();
    if (count == 0) return {};
    uint32_t length = 0;  // bytes, the terminating zero included
    if (!api_->GetCapture(count - 1, nullptr, &length, nullptr) || length == 0) return {};
    std::string path(length, '\0');
    api_->GetCapture(count - 1, path.data(), &length, nullptr);
    path.resize(std::strlen(path.c_str()));
    return path;
}

bool RenderDocCapture::glHooked() {
    // RenderDoc's GL hooks take effect through its own exported dlopen, which only wins symbol
    // lookup when the library was preloaded; then "dlopen" resolves into librenderdoc.
    Dl_info info{};
    void* resolved = dlsym(RTLD_DEFAULT, "dlopen");
    return resolved && dladdr(resolved, &info) && info.dli_fname &&
           std::strstr(info.dli_fname, "librenderdoc") != nullptr;
}

}  // namespace fe::platform
