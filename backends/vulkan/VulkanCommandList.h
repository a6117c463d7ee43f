// Command recording into a VkCommandBuffer; see VulkanDevice.h for the synchronisation model.
#pragma once
#include <array>

#include "VulkanDevice.h"

namespace fe::vk {

class VulkanCommandList final : public gdi::CommandList {
public:
    explicit VulkanCommandList(VulkanDevice& device);
    ~VulkanCommandList() override;

    void beginRenderPass(const gdi::RenderPassDesc& desc) override;
    void endRenderPass() override;
    void setPipeline(gdi::PipelineHandle pipeline) override;
    void setViewport(const gdi::Viewport& viewport) override;
    void setScissor(const gdi::Rect& rect) override;
    void setVertexBuffer(uint32_t index, gdi::BufferHandle buffer, uint64_t offset) override;
    void setIndexBuffer(gdi::BufferHandle buffer, gdi::IndexType type, uint64_t offset) override;
    void setUniformBuffer(uint32_t slot, gdi::BufferHandle buffer, uint64_t offset, uint64_t size) override;
    void setStorageBuffer(uint32_t slot, gdi::BufferHandle buffer, uint64_t offset, uint64_t size) override;
    void setTexture(uint32_t slot, gdi::TextureHandle texture, gdi::SamplerHandle sampler) override;
    void setStorageTexture(uint32_t slot, gdi::TextureHandle texture, uint32_t mipLevel) override;
    void draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex, uint32_t firstInstance) override;
    void drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex, int32_t baseVertex,
                     uint32_t firstInstance) override;
    void dispatch(uint32_t x, uint32_t y, uint32_t z) override;
    void copyBuffer(gdi::BufferHandle dst, uint64_t dstOffset, gdi::BufferHandle src, uint64_t srcOffset,
                    uint64_t size) override;
    void copyTexture(gdi::TextureHandle dst, gdi::TextureHandle src, uint32_t mipLevel) override;
    void copyBufferToTexture(gdi::TextureHandle dst, uint32_t mipLevel, gdi::BufferHandle src, uint64_t srcOffset) override;
    void copyTextureToBuffer(gdi::BufferHandle dst, uint64_t dstOffset, gdi::TextureHandle src, uint32_t mipLevel) override;
    void beginTimer(gdi::TimerHandle timer) override;
    void endTimer(gdi::TimerHandle timer) override;
    void pushDebugGroup(const char* name) override;
    void popDebugGroup() override;
    uint64_t nativeCommandBuffer() override {
        ensureRecording();
        return uint64_t(cb_);
    }

    // For the device.
    VkCommandBuffer finish();
    void submitted(gdi::FenceValue value) { lastSubmit_ = value; recording_ = false; }
    static void fullBarrier(VkCommandBuffer cb);
    static void toGeneral(VkCommandBuffer cb, VkImage image, gdi::Format format, uint32_t mipLevels);
    void discardTexture(gdi::TextureHandle texture) override;
    void setAutomaticBarriers(bool enabled) override;
    void barrier(const gdi::TextureBarrier* barriers, uint32_t count) override;

private:
    void ensureRecording() {
        if (!recording_) [[unlikely]]
            beginRecording();
    }
    void beginRecording();
    void outsidePass(const char* what);
    void barrierIfWritten();
    void flushBindings();
    struct Binding {
        VkDescriptorType type;  // checked against the pipeline's at flush
        VkDescriptorBufferInfo buffer;
        VkDescriptorImageInfo image;
    };

    VulkanDevice& dev_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer cb_ = VK_NULL_HANDLE;
    bool recording_ = false;
    bool inPass_ = false;
    bool passHasLabel_ = false;
    bool written_ = false;  // a command since the last barrier wrote memory
    bool automaticBarriers_ = true;
    gdi::FenceValue lastSubmit_ = 0;
    Pipeline* pipeline_ = nullptr;
    bool computeBound_ = false;  // pipeline_ is a compute pipeline (draws are errors)
    gdi::Rect renderArea_;
    std::array<Binding, 64> bindings_{};
    // Descriptor writes for the pipeline writesFor_, each pointing at its slot in bindings_.
    std::array<VkWriteDescriptorSet, 64> writes_{};
    const Pipeline* writesFor_ = nullptr;
    uint64_t boundSlots_ = 0;
    // Slots set since they were last pushed. Push descriptors may be updated incrementally
    // until a pipeline with another layout disturbs the set, which makes every slot dirty.
    uint64_t dirtySlots_ = ~uint64_t(0);
    int debugDepth_ = 0;
};

}  // namespace fe::vk
