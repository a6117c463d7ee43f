// The vulkan-glfw backend's window: a GLFW window with no client API (platform/GlfwWindow,
// shared with gl-glfw), its VkSurfaceKHR, and a VK_KHR_swapchain swap chain that
// Device::present copies textures into.
//
// One present: acquire an image (signalling the frame slot's semaphore) -> one command buffer:
// a full barrier after earlier submissions, an RGBA8_SRGB texture copied bit for bit into a
// UNORM staging image (a blit from sRGB would decode it), a NEAREST blit into the swap-chain
// image (UNORM to UNORM is exact, and the blit swizzles RGBA into the surface's BGRA), the
// image moved to PRESENT_SRC -> submit (waits for the acquire semaphore, signals the image's
// present semaphore and the slot's fence) -> vkQueuePresentKHR.
//  - Acquire semaphores belong to frame slots: a slot is reused only after its fence, so the
//    submission that waited on its semaphore is over.
//  - Present semaphores belong to swap-chain images: an image's is signalled again only once
//    that image was acquired again, i.e. after the presentation that waited on it.
//  - The swap chain is recreated when the window's size differs from its extent (present sizes
//    the window to the texture) and after OUT_OF_DATE / SUBOPTIMAL, once the queue is idle.
#pragma once
#include <stdexcept>
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"
#include "fe/gdi/Image.h"

namespace fe::platform {
class GlfwWindow;
}

namespace fe::vk {

// VK_ERROR_DEVICE_LOST from a present's own calls (what() names the call).
struct SwapchainDeviceLost : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class VulkanSwapchain {
public:
    // Opens the (hidden) window; throws gdi::Error saying why not.
    explicit VulkanSwapchain(bool vsync);
    ~VulkanSwapchain();
    VulkanSwapchain(const VulkanSwapchain&) = delete;
    VulkanSwapchain& operator=(const VulkanSwapchain&) = delete;

    // Before the device exists: the instance extensions a surface needs, then the surface.
    std::vector<const char*> instanceExtensions() const;
    void createSurface(VkInstance instance);
    bool canPresent(VkPhysicalDevice physical, uint32_t queueFamily) const;
    // Once it exists: picks the surface format and present mode, makes the per-frame objects.
    void attach(VkPhysicalDevice physical, VkDevice device, VkQueue queue, uint32_t queueFamily);
    const std::string& presentMode() const { return presentModeText_; }

    struct Source {
        VkImage image = VK_NULL_HANDLE;  // in VK_IMAGE_LAYOUT_GENERAL, RGBA8 or BGRA8 (or sRGB)
        uint32_t width = 0, height = 0;
        bool srgb = false;
        bool bgra = false;
    };
    // Shows `source` in the window, sized to it; false once the user has closed the window.
    bool present(const Source& source);
    gdi::Image readWindow() const;
    gdi::InputState input() const;

    // Destroys every Vulkan object, the surface included, after waiting for the queue: call
    // before destroying the device and the instance. The window goes with the object.
    void release();

private:
    void recreate(uint32_t width, uint32_t height);
    void destroyChain(VkSwapchainKHR chain);
    void ensureStaging(uint32_t width, uint32_t height, VkFormat format);
    void record(VkCommandBuffer cb, VkImage target, const Source& source);

    struct Frame {
        VkCommandBuffer commands = VK_NULL_HANDLE;
        VkFence done = VK_NULL_HANDLE;  // created signalled
        VkSemaphore acquired = VK_NULL_HANDLE;
    };
    static constexpr uint32_t kFrames = 2;

    bool vsync_ = true;
    std::unique_ptr<platform::GlfwWindow> window_;
    VkInstance instance_ = VK_NULL_HANDLE;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    VkSurfaceFormatKHR format_{};
    VkPresentModeKHR mode_ = VK_PRESENT_MODE_FIFO_KHR;
    std::string presentModeText_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    std::array<Frame, kFrames> frames_{};
    uint32_t frame_ = 0;

    VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
    VkExtent2D extent_{};
    bool stale_ = false;  // OUT_OF_DATE / SUBOPTIMAL seen: recreate before the next acquire
    std::vector<VkImage> images_;
    std::vector<VkSemaphore> presentReady_;  // one per swap-chain image

    // The UNORM copy of an sRGB texture, blit source (bytes unchanged).
    VkImage staging_ = VK_NULL_HANDLE;
    VkDeviceMemory stagingMemory_ = VK_NULL_HANDLE;
    VkExtent2D stagingExtent_{};
    VkFormat stagingFormat_ = VK_FORMAT_UNDEFINED;

    uint32_t shownWidth_ = 0, shownHeight_ = 0;  // what the last present put on screen
};

}  // namespace fe::vk
