// The vulkan-glfw window: surface, swap chain, present (see VulkanSwapchain.h), and the
// VulkanDevice members that use them.
#include "VulkanSwapchain.h"
#include "VulkanFaults.h"

#include <algorithm>

#include "VulkanCommandList.h"
#include "VulkanDevice.h"
#include "fe/gdi/Validation.h"
#include "platform/GlfwWindow.h"

namespace fe::vk {

// The fault trace names this file's native calls "vkXxx (swap chain)": the fault sweep injects
// into the first call of each named site, and the device's own vkCreateSemaphore comes first.

namespace {
// A lost device during present: VulkanDevice::present turns it into the device's lost state.
void checkPresent(VkResult r, const char* call) {
    if (r == VK_ERROR_DEVICE_LOST) throw SwapchainDeviceLost(call);
    check(r, call);
}
// Long enough for any software rasterizer; a hung presentation engine becomes an error.
constexpr uint64_t kAcquireTimeoutNs = 10'000'000'000ull;

const char* modeName(VkPresentModeKHR m) {
    switch (m) {
        case VK_PRESENT_MODE_IMMEDIATE_KHR:
            return "IMMEDIATE";
        case VK_PRESENT_MODE_MAILBOX_KHR:
            return "MAILBOX";
        case VK_PRESENT_MODE_FIFO_KHR:
            return "FIFO";
        case VK_PRESENT_MODE_FIFO_RELAXED_KHR:
            return "FIFO_RELAXED";
        default:
            return "other";
    }
}

VkImageMemoryBarrier imageBarrier(VkImage image, VkImageLayout from, VkImageLayout to,
                                  VkAccessFlags src, VkAccessFlags dst) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = src;
    b.dstAccessMask = dst;
    b.oldLayout = from;
    b.newLayout = to;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    return b;
}

void barrier(VkCommandBuffer cb, VkPipelineStageFlags src, VkPipelineStageFlags dst,
             const VkImageMemoryBarrier& b) {
    vkCmdPipelineBarrier(cb, src, dst, 0, 0, nullptr, 0, nullptr, 1, &b);
}
}  // namespace

VulkanSwapchain::VulkanSwapchain(bool vsync)
    : vsync_(vsync),
      window_(std::make_unique<platform::GlfwWindow>(platform::GlfwWindow::Api::Vulkan, false)) {}

VulkanSwapchain::~VulkanSwapchain() { release(); }

std::vector<const char*> VulkanSwapchain::instanceExtensions() const {
    uint32_t n = 0;
    const char** names =
        window_->function<const char** (*)(uint32_t*)>("glfwGetRequiredInstanceExtensions")(&n);
    if (!names)  // the loader lists them only when a driver supports them
        throw gdi::Error(
            "GLFW: Vulkan offers no surface extensions for this window system (no Vulkan driver? apt-get "
            "install mesa-vulkan-drivers)");
    return {names, names + n};
}

void VulkanSwapchain::createSurface(VkInstance instance) {
    // GLFWwindow* passed as void*: no GLFW header above the platform layer.
    auto create = window_->function<VkResult (*)(VkInstance, void*, const VkAllocationCallbacks*,
                                                 VkSurfaceKHR*)>("glfwCreateWindowSurface");
    check(create(instance, window_->handle(), nullptr, &surface_), "glfwCreateWindowSurface");
    instance_ = instance;
}

bool VulkanSwapchain::canPresent(VkPhysicalDevice physical, uint32_t queueFamily) const {
    VkBool32 supported = VK_FALSE;
    return vkGetPhysicalDeviceSurfaceSupportKHR(physical, queueFamily, surface_, &supported) ==
               VK_SUCCESS &&
           supported;
}

void VulkanSwapchain::attach(VkPhysicalDevice physical, VkDevice device, VkQueue queue,
                             uint32_t queueFamily) {
    physical_ = physical, device_ = device, queue_ = queue;

    // An 8-bit UNORM format the blit can write: bytes reach the screen as the texture has them
    // (an _SRGB swap chain would mean "encode on write"). Textures are R8G8B8A8 and blit from it.
    uint32_t n = 0;
    check(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface_, &n, nullptr),
          "vkGetPhysicalDeviceSurfaceFormatsKHR");
    std::vector<VkSurfaceFormatKHR> formats(n);
    check(vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface_, &n, formats.data()),
          "vkGetPhysicalDeviceSurfaceFormatsKHR");
    auto features = [&](VkFormat f) {
        VkFormatProperties p;
        vkGetPhysicalDeviceFormatProperties(physical, f, &p);
        return p.optimalTilingFeatures;
    };
    if (!(features(VK_FORMAT_R8G8B8A8_UNORM) & VK_FORMAT_FEATURE_BLIT_SRC_BIT))
        throw gdi::Error(
            "Vulkan: R8G8B8A8_UNORM cannot be a blit source on this device, so present cannot copy to the window");
    bool found = false;
    for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
        for (const VkSurfaceFormatKHR& f : formats)
            if (!found && f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR &&
                (features(want) & VK_FORMAT_FEATURE_BLIT_DST_BIT))
                format_ = f, found = true;
    if (!found)
        throw gdi::Error(
            "Vulkan: the window's surface offers no B8G8R8A8_UNORM or R8G8B8A8_UNORM format to blit into (" +
            std::to_string(n) + " formats offered)");

    check(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface_, &n, nullptr),
          "vkGetPhysicalDeviceSurfacePresentModesKHR");
    std::vector<VkPresentModeKHR> modes(n);
    check(vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface_, &n, modes.data()),
          "vkGetPhysicalDeviceSurfacePresentModesKHR");
    auto has = [&](VkPresentModeKHR m) {
        return std::find(modes.begin(), modes.end(), m) != modes.end();
    };
    // FIFO is the one mode every surface has: vsync on. Off: IMMEDIATE tears but never waits;
    // MAILBOX does not wait either and replaces queued frames.
    mode_ = VK_PRESENT_MODE_FIFO_KHR;
    if (!vsync_ && has(VK_PRESENT_MODE_IMMEDIATE_KHR))
        mode_ = VK_PRESENT_MODE_IMMEDIATE_KHR;
    else if (!vsync_ && has(VK_PRESENT_MODE_MAILBOX_KHR))
        mode_ = VK_PRESENT_MODE_MAILBOX_KHR;
    presentModeText_ = std::string(modeName(mode_)) + (vsync_ ? " (vsync on)" : " (vsync off)");
    if (!vsync_ && mode_ == VK_PRESENT_MODE_FIFO_KHR)
        presentModeText_ =
            "FIFO (vsync off asked, but the surface has neither IMMEDIATE nor MAILBOX)";

    VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pci.queueFamilyIndex = queueFamily;
    check(nativeAllocation("vkCreateCommandPool (swap chain)",
                           [&] { return vkCreateCommandPool(device_, &pci, nullptr, &pool_); }),
          "vkCreateCommandPool");
    for (Frame& f : frames_) {
        VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
        ai.commandPool = pool_;
        ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        ai.commandBufferCount = 1;
        check(nativeAllocation("vkAllocateCommandBuffers (swap chain)",
                               [&] { return vkAllocateCommandBuffers(device_, &ai, &f.commands); }),
              "vkAllocateCommandBuffers");
        VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        fci.flags = VK_FENCE_CREATE_SIGNALED_BIT;  // the first use of a slot waits for nothing
        check(nativeAllocation("vkCreateFence (swap chain)",
                               [&] { return vkCreateFence(device_, &fci, nullptr, &f.done); }),
              "vkCreateFence");
        VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        check(nativeAllocation(
                  "vkCreateSemaphore (swap chain)",
                  [&] { return vkCreateSemaphore(device_, &sci, nullptr, &f.acquired); }),
              "vkCreateSemaphore");
    }
}

void VulkanSwapchain::recreate(uint32_t width, uint32_t height) {
    // Nothing may still use the old images or their semaphores; vkQueueWaitIdle also covers
    // the presentations queued so far.
    check(vkQueueWaitIdle(queue_), "vkQueueWaitIdle");
    VkSurfaceCapabilitiesKHR caps;
    check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical_, surface_, &caps),
          "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
    VkExtent2D extent = caps.currentExtent;
    if (extent.width == UINT32_MAX)  // the surface takes the swap chain's size: the window's
        extent = {std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width),
                  std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height)};
    if (extent.width == 0 || extent.height == 0) {  // minimised: nothing can be shown
        destroyChain(swapchain_);
        swapchain_ = VK_NULL_HANDLE, extent_ = {};
        return;
    }
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw gdi::Error(
            "Vulkan: the window's swap-chain images cannot be copied into (no TRANSFER_DST usage)");
    // One more image than the minimum, so acquiring never waits for the image on screen.
    uint32_t count = caps.minImageCount + 1;
    if (caps.maxImageCount) count = std::min(count, caps.maxImageCount);

    VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
    ci.surface = surface_;
    ci.minImageCount = count;
    ci.imageFormat = format_.format;
    ci.imageColorSpace = format_.colorSpace;
    ci.imageExtent = extent;
    ci.imageArrayLayers = 1;
    ci.imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.preTransform = caps.currentTransform;
    ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
    if (!(caps.supportedCompositeAlpha & ci.compositeAlpha))  // any mode the surface has
        ci.compositeAlpha = VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha &
                                                        -caps.supportedCompositeAlpha);
    ci.presentMode = mode_;
    ci.clipped = VK_TRUE;
    ci.oldSwapchain = swapchain_;
    VkSwapchainKHR created = VK_NULL_HANDLE;
    check(nativeAllocation("vkCreateSwapchainKHR (swap chain)",
                           [&] { return vkCreateSwapchainKHR(device_, &ci, nullptr, &created); }),
          "vkCreateSwapchainKHR");
    destroyChain(swapchain_);
    swapchain_ = created;
    extent_ = extent;
    stale_ = false;

    uint32_t n = 0;
    check(vkGetSwapchainImagesKHR(device_, swapchain_, &n, nullptr), "vkGetSwapchainImagesKHR");
    images_.resize(n);
    check(vkGetSwapchainImagesKHR(device_, swapchain_, &n, images_.data()),
          "vkGetSwapchainImagesKHR");
    presentReady_.assign(n, VK_NULL_HANDLE);
    for (VkSemaphore& s : presentReady_) {
        VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
        check(nativeAllocation("vkCreateSemaphore (swap chain)",
                               [&] { return vkCreateSemaphore(device_, &sci, nullptr, &s); }),
              "vkCreateSemaphore");
    }
}

// The swap chain and its per-image semaphores; the caller has waited for the queue.
void VulkanSwapchain::destroyChain(VkSwapchainKHR chain) {
    for (VkSemaphore s : presentReady_) vkDestroySemaphore(device_, s, nullptr);
    presentReady_.clear();
    images_.clear();
    if (chain) vkDestroySwapchainKHR(device_, chain, nullptr);
}

void VulkanSwapchain::ensureStaging(uint32_t width, uint32_t height, VkFormat format) {
    if (staging_ && stagingExtent_.width == width && stagingExtent_.height == height &&
        stagingFormat_ == format)
        return;
    check(vkQueueWaitIdle(queue_), "vkQueueWaitIdle");  // the last present may still read it
    vkDestroyImage(device_, staging_, nullptr), staging_ = VK_NULL_HANDLE;
    vkFreeMemory(device_, stagingMemory_, nullptr), stagingMemory_ = VK_NULL_HANDLE;
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = format;
    ci.extent = {width, height, 1};
    ci.mipLevels = ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    check(nativeAllocation("vkCreateImage (swap chain)",
                           [&] { return vkCreateImage(device_, &ci, nullptr, &staging_); }),
          "vkCreateImage");
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, staging_, &req);
    VkPhysicalDeviceMemoryProperties props;
    vkGetPhysicalDeviceMemoryProperties(physical_, &props);
    // One image the size of a window, reallocated only on resize: a dedicated allocation
    // rather than a share of the device's sub-allocator.
    uint32_t type = UINT32_MAX;
    for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
        if ((req.memoryTypeBits & (1u << i)) &&
            (props.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT))
            type = i;
    for (uint32_t i = 0; i < props.memoryTypeCount && type == UINT32_MAX; ++i)
        if (req.memoryTypeBits & (1u << i)) type = i;
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = type;
    check(
        nativeAllocation("vkAllocateMemory (swap chain)",
                         [&] { return vkAllocateMemory(device_, &ai, nullptr, &stagingMemory_); }),
        "vkAllocateMemory");
    check(vkBindImageMemory(device_, staging_, stagingMemory_, 0), "vkBindImageMemory");
    stagingExtent_ = {width, height};
    stagingFormat_ = format;
}

void VulkanSwapchain::record(VkCommandBuffer cb, VkImage target, const Source& src) {
    VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(nativeAllocation("vkBeginCommandBuffer (swap chain)",
                           [&] { return vkBeginCommandBuffer(cb, &bi); }),
          "vkBeginCommandBuffer");
    VulkanCommandList::fullBarrier(cb);  // after every earlier submission's writes to the texture

    VkImage from = src.image;
    VkImageLayout fromLayout = VK_IMAGE_LAYOUT_GENERAL;
    if (src.srgb) {
        // A blit would decode sRGB to linear; a copy moves the bits into the UNORM twin.
        barrier(
            cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
            imageBarrier(staging_, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         0, VK_ACCESS_TRANSFER_WRITE_BIT));
        VkImageCopy copy{};
        copy.srcSubresource = copy.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        copy.extent = {src.width, src.height, 1};
        vkCmdCopyImage(cb, src.image, VK_IMAGE_LAYOUT_GENERAL, staging_,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
        barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                imageBarrier(staging_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                             VK_ACCESS_TRANSFER_READ_BIT));
        from = staging_;
        fromLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    }

    // The acquire semaphore's wait blocks the transfer stage; this transition chains after it.
    barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
            imageBarrier(target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                         VK_ACCESS_TRANSFER_WRITE_BIT));
    const uint32_t w = std::min(src.width, extent_.width), h = std::min(src.height, extent_.height);
    if (w != extent_.width ||
        h != extent_.height) {  // a window larger than the image: black around it
        VkClearColorValue black{};
        black.float32[3] = 1.0f;
        VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(cb, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1, &range);
        barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                imageBarrier(target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                             VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                             VK_ACCESS_TRANSFER_WRITE_BIT));
    }
    // Same size, NEAREST: every texel lands on one pixel, converted per channel (R to R), so the
    // blit is the RGBA <-> BGRA swizzle where needed and the colours stay the same. Row 0 is the top on both.
    VkImageBlit blit{};
    blit.srcSubresource = blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = blit.dstOffsets[1] = {int32_t(w), int32_t(h), 1};
    vkCmdBlitImage(cb, from, fromLayout, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit,
                   VK_FILTER_NEAREST);
    barrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
            imageBarrier(target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                         VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_ACCESS_TRANSFER_WRITE_BIT, 0));
    check(
        nativeAllocation("vkEndCommandBuffer (swap chain)", [&] { return vkEndCommandBuffer(cb); }),
        "vkEndCommandBuffer");
}

bool VulkanSwapchain::present(const Source& src) {
    const platform::GlfwWindow::Size size = window_->prepare(src.width, src.height);
    if (src.srgb)  // the UNORM twin of the texture's format takes its bits
        ensureStaging(src.width, src.height,
                      src.bgra ? VK_FORMAT_B8G8R8A8_UNORM : VK_FORMAT_R8G8B8A8_UNORM);
    for (int attempt = 0;; ++attempt) {
        if (!swapchain_ || stale_ || extent_.width != size.width || extent_.height != size.height)
            recreate(size.width, size.height);
        if (!swapchain_) return window_->poll();  // minimised

        Frame& f = frames_[frame_];
        checkPresent(vkWaitForFences(device_, 1, &f.done, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        uint32_t index = 0;
        VkResult r = vkAcquireNextImageKHR(device_, swapchain_, kAcquireTimeoutNs, f.acquired,
                                           VK_NULL_HANDLE, &index);
        if (r == VK_ERROR_OUT_OF_DATE_KHR &&
            attempt < 3) {  // no image, semaphore untouched: recreate
            stale_ = true;
            continue;
        }
        if (r == VK_SUBOPTIMAL_KHR)
            stale_ = true;  // still presentable: show this frame, recreate for the next
        else if (r != VK_SUCCESS)
            checkPresent(r, "vkAcquireNextImageKHR");

        check(vkResetCommandBuffer(f.commands, 0), "vkResetCommandBuffer");
        record(f.commands, images_[index], src);
        check(vkResetFences(device_, 1, &f.done), "vkResetFences");
        const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_TRANSFER_BIT;
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.waitSemaphoreCount = 1;
        si.pWaitSemaphores = &f.acquired;
        si.pWaitDstStageMask = &waitStage;
        si.commandBufferCount = 1;
        si.pCommandBuffers = &f.commands;
        si.signalSemaphoreCount = 1;
        si.pSignalSemaphores = &presentReady_[index];
        checkPresent(nativeSubmission("vkQueueSubmit (swap chain)",
                                      [&] { return vkQueueSubmit(queue_, 1, &si, f.done); }),
                     "vkQueueSubmit");

        VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
        pi.waitSemaphoreCount = 1;
        pi.pWaitSemaphores = &presentReady_[index];
        pi.swapchainCount = 1;
        pi.pSwapchains = &swapchain_;
        pi.pImageIndices = &index;
        r = nativeSubmission("vkQueuePresentKHR (swap chain)",
                             [&] { return vkQueuePresentKHR(queue_, &pi); });
        // Out of date or suboptimal: the semaphore wait still happens; recreate next time.
        if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR)
            stale_ = true;
        else
            checkPresent(r, "vkQueuePresentKHR");
        frame_ = (frame_ + 1) % kFrames;
        break;
    }
    shownWidth_ = std::min(src.width, extent_.width);
    shownHeight_ = std::min(src.height, extent_.height);
    return window_->poll();
}

gdi::Image VulkanSwapchain::readWindow() const { return window_->read(shownWidth_, shownHeight_); }
gdi::InputState VulkanSwapchain::input() const { return window_->input(); }

void VulkanSwapchain::release() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        destroyChain(swapchain_);
        swapchain_ = VK_NULL_HANDLE;
        for (Frame& f : frames_) {
            vkDestroyFence(device_, f.done, nullptr);
            vkDestroySemaphore(device_, f.acquired, nullptr);
            f = {};
        }
        vkDestroyCommandPool(device_, pool_, nullptr), pool_ = VK_NULL_HANDLE;
        vkDestroyImage(device_, staging_, nullptr), staging_ = VK_NULL_HANDLE;
        vkFreeMemory(device_, stagingMemory_, nullptr), stagingMemory_ = VK_NULL_HANDLE;
        device_ = VK_NULL_HANDLE;
    }
    if (surface_) vkDestroySurfaceKHR(instance_, surface_, nullptr), surface_ = VK_NULL_HANDLE;
}

// ---------------------------------------------------------------------------------------------
// VulkanDevice's window members
// ---------------------------------------------------------------------------------------------
std::unique_ptr<gdi::Device> createVulkanWindowDevice(bool validation, bool vsync,
                                                      bool robustBufferAccess) {
    return std::make_unique<VulkanDevice>(validation, std::make_unique<VulkanSwapchain>(vsync),
                                          robustBufferAccess);
}

bool VulkanDevice::present(gdi::TextureHandle h) {
    const DeviceCall call(*this);
    loss_.check("present");
    if (!swapchain_) return gdi::Device::present(h);
    Texture& t = texture(h);
    gdi::validate::notAView(t.viewOf != 0, t.name, "present");
    gdi::validate::presentTexture(t.desc, t.name);
    presentedSinceIdle_ = true;  // the swap chain's copy is not behind a device fence
    if (VkCommandBuffer init = takeInitialTransitions()) {  // the presented texture may be new
        VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        si.commandBufferCount = 1;
        si.pCommandBuffers = &init;
        check(vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
        check(vkQueueWaitIdle(queue_), "vkQueueWaitIdle");
        vkFreeCommandBuffers(device_, immediatePool_, 1, &init);
    }
    try {
        return swapchain_->present(
            {t.image, t.desc.width, t.desc.height,
             t.desc.format == gdi::Format::RGBA8_SRGB || t.desc.format == gdi::Format::BGRA8_SRGB,
             t.desc.format == gdi::Format::BGRA8 || t.desc.format == gdi::Format::BGRA8_SRGB});
    } catch (const SwapchainDeviceLost& e) {
        throw loss_.lose("vulkan", std::string(e.what()) + " returned VK_ERROR_DEVICE_LOST");
    }
}

gdi::InputState VulkanDevice::input() const {
    return swapchain_ ? swapchain_->input() : gdi::InputState{};
}

gdi::Image VulkanDevice::readWindow() {
    loss_.check("readWindow");
    if (!swapchain_) return gdi::Device::readWindow();
    return swapchain_->readWindow();
}

}  // namespace fe::vk
