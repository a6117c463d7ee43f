// gdi::FrameCapture over RenderDoc's in-application API (platform/RenderDocCapture.h). Layer 4:
// it knows that GL captures must start and end on the context's thread.
#include "fe/gdi/Backend.h"
#include "gl/GlBackend.h"
#include "platform/RenderDocCapture.h"

namespace fe::gdi {

namespace {

class RenderDocFrameCapture final : public FrameCapture {
public:
    explicit RenderDocFrameCapture(std::unique_ptr<platform::RenderDocCapture> rd)
        : rd_(std::move(rd)) {}

    void begin(Device& device) override {
        const std::string& backend = device.info().backend;
        if (backend == "gl-osmesa")
            throw Error(
                "RenderDoc cannot capture gl-osmesa (it has no OSMesa hooks): use vulkan or gl-egl");
        if (isGl(backend) && !platform::RenderDocCapture::glHooked())
            throw Error("RenderDoc captures " + backend +
                        " only when fe starts with LD_PRELOAD=/usr/lib/librenderdoc.so "
                        "(it hooks GL by symbol interposition); vulkan needs nothing");
        device.waitIdle();  // the capture starts between frames
        onDeviceThread(device, [&] { rd_->startFrame(); });
    }

    std::string end(Device& device) override {
        device.waitIdle();
        bool written = false;
        onDeviceThread(device, [&] { written = rd_->endFrame(); });
        if (!written)
            throw Error(
                "RenderDoc wrote no capture (was the device created after FrameCapture::load?)");
        return rd_->lastCapturePath();
    }

private:
    static bool isGl(const std::string& backend) { return backend.rfind("gl-", 0) == 0; }
    // GL: RenderDoc must see the thread its context is current on; elsewhere it crashes.
    static void onDeviceThread(Device& device, const std::function<void()>& task) {
        if (isGl(device.info().backend))
            gl::runOnContextThread(device, task);
        else
            task();
    }
    std::unique_ptr<platform::RenderDocCapture> rd_;
};

}  // namespace

std::unique_ptr<FrameCapture> FrameCapture::load(const std::string& path) {
    std::string why;
    auto rd = platform::RenderDocCapture::load(why);
    if (!rd) throw Error("RenderDoc capture unavailable: " + why);
    rd->setCapturePath(path);
    return std::make_unique<RenderDocFrameCapture>(std::move(rd));
}

}  // namespace fe::gdi
