// Layer 5 (Communication): a headless swap chain, a ring of colour images that frames render
// into and that can be read back once presented (the window-less stand-in for a surface).
#pragma once
#include <vector>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"

namespace fe::render {

struct SwapChainDesc {
    uint32_t width = 0;
    uint32_t height = 0;
    gdi::Format format = gdi::Format::RGBA16F;  // linear radiance; tonemapping happens at output
    uint32_t imageCount = 3;
};

class SwapChain {
public:
    SwapChain(gdi::Device& device, const SwapChainDesc& desc);
    ~SwapChain();
    SwapChain(const SwapChain&) = delete;
    SwapChain& operator=(const SwapChain&) = delete;

    // The next image to render into; waits until its previous frame completed.
    gdi::TextureHandle acquire();
    // Marks the acquired image as presented by the frame that signals `fence`.
    void present(gdi::FenceValue fence);
    // Reads the most recently presented image back (waits for its frame).
    gdi::Image readLastPresented();

    const SwapChainDesc& desc() const { return desc_; }

private:
    struct Entry {
        gdi::TextureHandle texture;
        gdi::FenceValue fence = 0;
    };
    gdi::DeviceObjects objects_;
    gdi::Device& device_;
    SwapChainDesc desc_;
    std::vector<Entry> images_;
    uint32_t next_ = 0;
    int acquired_ = -1;
    int lastPresented_ = -1;
};

}  // namespace fe::render
