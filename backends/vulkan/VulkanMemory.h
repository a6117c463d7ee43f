// Device-memory sub-allocation: a few large VkDeviceMemory blocks per memory type, carved
// into placements with a first-fit free list. Vulkan drivers limit allocation counts
// (maxMemoryAllocationCount, often 4096) and each vkAllocateMemory is slow, so one allocation
// per resource does not scale. Also the base the render graph's transient aliasing builds on.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace fe::vk {

struct Allocation {
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = 0;
    void* mapped = nullptr;  // host pointer at `offset` for host-visible memory
    uint32_t block = UINT32_MAX;
    explicit operator bool() const { return memory != VK_NULL_HANDLE; }
};

// Transient: attachments whose contents live inside a pass (lazily allocated memory first).
enum class MemoryUsage { GpuOnly, Upload, Readback, Transient };

class MemoryAllocator {
public:
    MemoryAllocator(VkPhysicalDevice physicalDevice, VkDevice device);
    ~MemoryAllocator();
    MemoryAllocator(const MemoryAllocator&) = delete;
    MemoryAllocator& operator=(const MemoryAllocator&) = delete;

    // `object` names what the memory is for, in errors (gdi::describeObject).
    Allocation allocate(const VkMemoryRequirements& req, MemoryUsage usage,
                        const std::string& object);
    void free(const Allocation& a);

    struct Stats {
        VkDeviceSize reserved = 0;  // sum of block sizes
        VkDeviceSize used = 0;      // sum of live placements
        uint32_t blocks = 0;
        uint32_t placements = 0;
    };
    Stats stats() const;

private:
    struct Block {
        VkDeviceMemory memory = VK_NULL_HANDLE;
        VkDeviceSize size = 0;
        uint32_t typeIndex = 0;
        void* mapped = nullptr;
        bool dedicated = false;
        std::map<VkDeviceSize, VkDeviceSize> freeRanges;  // offset -> size, coalesced
        uint32_t live = 0;
    };
    uint32_t chooseType(uint32_t typeBits, MemoryUsage usage) const;
    uint32_t newBlock(uint32_t typeIndex, VkDeviceSize size, bool dedicated,
                      const std::string& object);

    VkDevice device_;
    VkPhysicalDeviceMemoryProperties props_{};
    VkDeviceSize granularity_ = 1;
    std::vector<std::unique_ptr<Block>> blocks_;
    VkDeviceSize used_ = 0;
    uint32_t placements_ = 0;
    static constexpr VkDeviceSize kBlockSize = 32ull << 20;
};

}  // namespace fe::vk
