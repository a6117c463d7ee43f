#include "SwapChain.h"

#include <string>

namespace fe::render {

SwapChain::SwapChain(gdi::Device& device, const SwapChainDesc& desc)
    : objects_(device), device_(device), desc_(desc) {
    if (desc.imageCount == 0 || desc.imageCount > 8)
        throw gdi::Error("SwapChain: imageCount must be 1..8");
    for (uint32_t i = 0; i < desc.imageCount; ++i) {
        std::string name = "swapchain " + std::to_string(i);
        images_.push_back({objects_.add(device.createTexture(
                               {.format = desc.format,
                                .width = desc.width,
                                .height = desc.height,
                                .usage = gdi::TextureUsage::RenderTarget |
                                         gdi::TextureUsage::Sampled | gdi::TextureUsage::CopySrc,
                                .debugName = name.c_str()})),
                           0});
    }
}

SwapChain::~SwapChain() {
    for (Entry& e : images_)
        if (e.fence) device_.waitOrLost(e.fence);  // a destructor must not throw
}

gdi::TextureHandle SwapChain::acquire() {
    if (acquired_ >= 0) throw gdi::Error("SwapChain::acquire: previous image not presented");
    Entry& e = images_[next_];
    if (e.fence) device_.wait(e.fence);
    acquired_ = int(next_);
    next_ = (next_ + 1) % images_.size();
    return e.texture;
}

void SwapChain::present(gdi::FenceValue fence) {
    if (acquired_ < 0) throw gdi::Error("SwapChain::present without acquire");
    images_[acquired_].fence = fence;
    lastPresented_ = acquired_;
    acquired_ = -1;
}

gdi::Image SwapChain::readLastPresented() {
    if (lastPresented_ < 0) throw gdi::Error("SwapChain: nothing presented yet");
    Entry& e = images_[lastPresented_];
    if (e.fence) device_.wait(e.fence);
    return device_.readTexture(e.texture);
}

}  // namespace fe::render
