// Entry point of the Vulkan backend; the only Vulkan symbol visible outside backends/vulkan.
#pragma once
#include <memory>

#include "fe/gdi/Device.h"

namespace fe::vk {
// Throws gdi::Error saying why when no usable Vulkan device exists (no loader, no ICD, missing
// required features).
// robustBufferAccess: enable the feature (DeviceCreateDesc::robustBufferAccess) where offered.
std::unique_ptr<gdi::Device> createVulkanDevice(bool validation, bool robustBufferAccess = false);
// The vulkan-glfw backend: the same device with a GLFW window, a surface and a swap chain
// (Device::present). `vsync`: FIFO; off: IMMEDIATE, else MAILBOX, else FIFO. Throws gdi::Error
// saying why when there is no display, no libglfw3, or no queue that can present.
std::unique_ptr<gdi::Device> createVulkanWindowDevice(bool validation, bool vsync,
                                                      bool robustBufferAccess = false);
}  // namespace fe::vk
