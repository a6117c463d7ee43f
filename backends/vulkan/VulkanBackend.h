// Entry point of the Vulkan backend; the only Vulkan symbol visible outside backends/vulkan.
#pragma once
#include <memory>

#include "fe/gdi/Device.h"

namespace fe::vk {
// Throws gdi::Error saying why when no usable Vulkan device exists (no loader, no ICD, missing
// required features).
std::unique_ptr<gdi::Device> createVulkanDevice(bool validation);
}  // namespace fe::vk
