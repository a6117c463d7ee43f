// Layer 3 (device-independent recording): command lists as data on any backend, for capture and
// replay.
//  - RecordingCommandList wraps a device's list: each call goes to that list first (so its
//    checks and errors are the device's), then becomes a record of CommandSet.inc in a stream.
//    Like any list it is used by one thread at a time; gdi::exclusiveUse (ExclusiveUse.h) checks
//    that, as the capture device does for the lists it hands out under validation.
//  - applyStream calls a stream's records on any device's list, mapping the handle ids it holds
//    to that device's objects, so a recording made on one backend runs on another.
//
//   RecordingCommandList rec(device, device.createCommandList());
//   rec.beginRenderPass(...); rec.draw(3); rec.endRenderPass();
//   auto stream = rec.takeStream();           // before or after submitting rec.inner()
//   auto list = other.createCommandList();
//   applyStream(*stream, other, *list, map);  // the same calls, on `other`
#pragma once
#include <memory>
#include <unordered_map>

#include "fe/gdi/CommandStream.h"

namespace fe::gdi {

class RecordingCommandList final : public CommandList {
public:
    RecordingCommandList(Device& device, std::unique_ptr<CommandList> inner);
    CommandList& inner() { return *inner_; }
    // The calls recorded since the last take (secondary lists executed here included).
    std::unique_ptr<cmd::CommandStream> takeStream();

    void beginRenderPass(const RenderPassDesc& desc) override;
    void endRenderPass() override;
    void setPipeline(PipelineHandle pipeline) override;
    void setViewport(const Viewport& viewport) override;
    void setScissor(const Rect& rect) override;
    void setBlendConstant(const std::array<float, 4>& rgba) override;
    void setStencilReference(uint8_t reference) override;
    void setDepthBias(float constant, float slope, float clamp) override;
    void setConstants(uint32_t offset, ByteSpan data) override;
    void setVertexBuffer(uint32_t index, BufferHandle buffer, uint64_t offset) override;
    void setIndexBuffer(BufferHandle buffer, IndexType type, uint64_t offset) override;
    void setUniformBuffer(uint32_t slot, BufferHandle buffer, uint64_t offset, uint64_t size) override;
    void setStorageBuffer(uint32_t slot, BufferHandle buffer, uint64_t offset, uint64_t size) override;
    void setTexture(uint32_t slot, TextureHandle texture, SamplerHandle sampler) override;
    void setStorageTexture(uint32_t slot, TextureHandle texture, uint32_t mipLevel) override;
    void draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex, uint32_t firstInstance) override;
    void drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex, int32_t baseVertex,
                     uint32_t firstInstance) override;
    void dispatch(uint32_t x, uint32_t y, uint32_t z) override;
    void drawIndirect(BufferHandle args, uint64_t offset, uint32_t drawCount, uint32_t stride) override;
    void drawIndexedIndirect(BufferHandle args, uint64_t offset, uint32_t drawCount, uint32_t stride) override;
    void drawIndirectCount(BufferHandle args, uint64_t offset, BufferHandle count, uint64_t countOffset, uint32_t maxDrawCount,
                           uint32_t stride) override;
    void drawIndexedIndirectCount(BufferHandle args, uint64_t offset, BufferHandle count, uint64_t countOffset,
                                  uint32_t maxDrawCount, uint32_t stride) override;
    void dispatchIndirect(BufferHandle args, uint64_t offset) override;
    void generateMips(TextureHandle texture) override;
    void copyBuffer(BufferHandle dst, uint64_t dstOffset, BufferHandle src, uint64_t srcOffset, uint64_t size) override;
    void clearBuffer(BufferHandle buffer, uint64_t offset, uint64_t size, uint32_t value) override;
    void copyTexture(TextureHandle dst, TextureHandle src, uint32_t mipLevel) override;
    void copyBufferToTexture(TextureHandle dst, Subresource at, BufferHandle src, uint64_t srcOffset) override;
    void copyTextureToBuffer(BufferHandle dst, uint64_t dstOffset, TextureHandle src, Subresource at) override;
    void copyBufferToTexture(TextureHandle dst, const TextureRegion& region, BufferHandle src, const TexelLayout& layout) override;
    void copyTextureToBuffer(BufferHandle dst, const TexelLayout& layout, TextureHandle src, const TextureRegion& region) override;
    void copyTexture(TextureHandle dst, const TextureRegion& dstAt, TextureHandle src, const TextureRegion& srcRegion) override;
    void beginTimer(TimerHandle timer) override;
    void endTimer(TimerHandle timer) override;
    void beginQuery(QuerySetHandle set, uint32_t index) override;
    void endQuery(QuerySetHandle set, uint32_t index) override;
    void writeTimestamp(QuerySetHandle set, uint32_t index) override;
    void resolveQueries(QuerySetHandle set, uint32_t first, uint32_t count, BufferHandle dst, uint64_t dstOffset) override;
    void pushDebugGroup(const char* name) override;
    void popDebugGroup() override;
    void insertDebugLabel(const char* name) override;
    void discardTexture(TextureHandle texture) override;
    void setAutomaticBarriers(bool enabled) override;
    void barrier(const TextureBarrier* barriers, uint32_t count) override;
    void barrier(const BufferBarrier* barriers, uint32_t count) override;
    void beginSecondary(const RenderPassDesc& pass) override;
    void endSecondary() override;
    void executeSecondary(std::span<CommandList* const> lists) override;
    using CommandList::barrier;
    using CommandList::executeSecondary;

private:
    template <class R, class T>
    void pushArray(std::span<const T> items);
    void pushName(const char* name, bool label);
    Device& device_;
    std::unique_ptr<CommandList> inner_;
    std::unique_ptr<cmd::CommandStream> stream_;
};

// Handle ids of the recording device -> the replaying device's. Ids missing from a map are
// used as they are when keepUnknown (right when both are one device), else they become an id no
// device has, so the replaying device refuses them (captures from files).
struct HandleMap {
    std::unordered_map<uint32_t, uint32_t> buffers, textures, samplers, pipelines, timers, querySets;
    bool keepUnknown = true;
    static constexpr uint32_t kUnknownId = 0xFFFFFFFFu;
};

// Watches and steers applyStream record by record in the primary stream (capture replay's pass
// snapshots, early stops and perturbations for fe bisect). A secondary stream is applied whole,
// as its ExecuteSecondary record.
class ApplyObserver {
public:
    virtual ~ApplyObserver() = default;
    // Before a record (`record` points at the record struct of `op`): false skips it.
    virtual bool before(cmd::Op op, const std::byte* record, CommandList& list) { return true; }
    // The pass a BeginRenderPass record is about to begin (handles already mapped): may change it.
    virtual void adjustPass(RenderPassDesc& pass) {}
    // After the record was applied to `list`; may record more on it, or set `stop`.
    virtual void after(cmd::Op op, const std::byte* record, CommandList& list) {}
    bool stop = false;  // the rest of the stream is not applied
};

// Calls `stream`'s records on `list` (a recording list of `device`), handles mapped through `map`.
// Secondary streams become secondary lists of `device`, begun for the pass that executes them.
void applyStream(const cmd::CommandStream& stream, Device& device, CommandList& list, const HandleMap& map = {},
                 ApplyObserver* observer = nullptr);

}  // namespace fe::gdi
