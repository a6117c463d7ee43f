#include "VulkanMemory.h"

#include <string>

#include "VulkanDevice.h"
#include "VulkanFaults.h"

namespace fe::vk {

MemoryAllocator::MemoryAllocator(VkPhysicalDevice physicalDevice, VkDevice device)
    : device_(device) {
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &props_);
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(physicalDevice, &p);
    // Buffers and optimal-tiling images share blocks; keeping every placement on the
    // granularity avoids the linear/optimal aliasing rule without tracking neighbours.
    granularity_ = p.limits.bufferImageGranularity;
}

MemoryAllocator::~MemoryAllocator() {
    for (auto& b : blocks_)
        if (b && b->memory) vkFreeMemory(device_, b->memory, nullptr);
}

uint32_t MemoryAllocator::chooseType(uint32_t typeBits, MemoryUsage usage) const {
    VkMemoryPropertyFlags required = 0, preferred = 0;
    switch (usage) {
        case MemoryUsage::GpuOnly:
            preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
            break;
        case MemoryUsage::Transient:
            preferred =
                VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT;
            break;
        case MemoryUsage::Upload:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            break;
        case MemoryUsage::Readback:
            required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
            preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
            break;
    }
    uint32_t best = UINT32_MAX;
    for (uint32_t i = 0; i < props_.memoryTypeCount; ++i) {
        if (!(typeBits & (1u << i))) continue;
        VkMemoryPropertyFlags f = props_.memoryTypes[i].propertyFlags;
        if ((f & required) != required) continue;
        if ((f & preferred) == preferred) return i;
        if (best == UINT32_MAX) best = i;
    }
    if (best == UINT32_MAX) throw gdi::Error("Vulkan: no memory type fits the resource");
    return best;
}

uint32_t MemoryAllocator::newBlock(uint32_t typeIndex, VkDeviceSize size, bool dedicated,
                                   const std::string& object) {
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = size;
    ai.memoryTypeIndex = typeIndex;
    auto b = std::make_unique<Block>();
    const std::string call = "vkAllocateMemory (" + std::to_string(size) + "-byte block)";
    check(nativeAllocation("vkAllocateMemory",
                           [&] { return vkAllocateMemory(device_, &ai, nullptr, &b->memory); }),
          call.c_str(), object);
    b->size = size;
    b->typeIndex = typeIndex;
    b->dedicated = dedicated;
    b->freeRanges[0] = size;
    if (props_.memoryTypes[typeIndex].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) {
        const VkResult r = nativeAllocation("vkMapMemory", [&] {  // persistently mapped
            return vkMapMemory(device_, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped);
        });
        if (r != VK_SUCCESS) {
            vkFreeMemory(device_, b->memory, nullptr);
            throwVk(r, "vkMapMemory", object);
        }
    }
    for (uint32_t i = 0; i < blocks_.size(); ++i)
        if (!blocks_[i]) {
            blocks_[i] = std::move(b);
            return i;
        }
    blocks_.push_back(std::move(b));
    return uint32_t(blocks_.size() - 1);
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& req, MemoryUsage usage,
                                     const std::string& object) {
    const uint32_t type = chooseType(req.memoryTypeBits, usage);
    const VkDeviceSize align = std::max<VkDeviceSize>(req.alignment, granularity_);
    const VkDeviceSize size = (req.size + granularity_ - 1) / granularity_ * granularity_;

    auto place = [&](uint32_t bi) -> Allocation {
        Block& b = *blocks_[bi];
        for (auto it = b.freeRanges.begin(); it != b.freeRanges.end(); ++it) {
            VkDeviceSize start = (it->first + align - 1) / align * align;
            VkDeviceSize end = it->first + it->second;
            if (start + size > end) continue;
            VkDeviceSize rangeStart = it->first;
            b.freeRanges.erase(it);
            if (start > rangeStart) b.freeRanges[rangeStart] = start - rangeStart;
            if (end > start + size) b.freeRanges[start + size] = end - (start + size);
            b.live++;
            used_ += size;
            placements_++;
            Allocation a;
            a.memory = b.memory;
            a.offset = start;
            a.size = size;
            a.block = bi;
            a.mapped = b.mapped ? static_cast<uint8_t*>(b.mapped) + start : nullptr;
            return a;
        }
        return {};
    };

    if (size > kBlockSize / 2) return place(newBlock(type, size, true, object));  // big: own block
    for (uint32_t i = 0; i < blocks_.size(); ++i)
        if (blocks_[i] && !blocks_[i]->dedicated && blocks_[i]->typeIndex == type)
            if (Allocation a = place(i)) return a;
    return place(newBlock(type, kBlockSize, false, object));
}

void MemoryAllocator::free(const Allocation& a) {
    if (!a || a.block >= blocks_.size() || !blocks_[a.block]) return;
    Block& b = *blocks_[a.block];
    used_ -= a.size;
    placements_--;
    b.live--;
    // Insert and coalesce with neighbours.
    auto it = b.freeRanges.emplace(a.offset, a.size).first;
    if (it != b.freeRanges.begin()) {
        auto prev = std::prev(it);
        if (prev->first + prev->second == it->first) {
            prev->second += it->second;
            b.freeRanges.erase(it);
            it = prev;
        }
    }
    auto next = std::next(it);
    if (next != b.freeRanges.end() && it->first + it->second == next->first) {
        it->second += next->second;
        b.freeRanges.erase(next);
    }
    if (b.live == 0 && b.dedicated) {
        vkFreeMemory(device_, b.memory, nullptr);
        blocks_[a.block].reset();
    }
}

MemoryAllocator::Stats MemoryAllocator::stats() const {
    Stats s;
    for (auto& b : blocks_)
        if (b) {
            s.reserved += b->size;
            s.blocks++;
        }
    s.used = used_;
    s.placements = placements_;
    return s;
}

}  // namespace fe::vk
