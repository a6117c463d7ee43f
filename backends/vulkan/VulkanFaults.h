// Native allocations and submissions go through these, so tests can make the N-th one fail
// (fe/gdi/Faults.h) with the VkResult a real failure returns; the call is then not made.
#pragma once
#include <vulkan/vulkan.h>

#include "fe/gdi/Faults.h"

namespace fe::vk {

// `name`: the Vulkan call, as the fault trace names the site.
template <class Call>
VkResult nativeAllocation(const char* name, Call&& call) {
    return gdi::fault::hit(gdi::fault::Site::Allocation, name) ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                                                               : call();
}

template <class Call>
VkResult nativeSubmission(const char* name, Call&& call) {
    return gdi::fault::hit(gdi::fault::Site::Submission, name) ? VK_ERROR_DEVICE_LOST : call();
}

}  // namespace fe::vk
