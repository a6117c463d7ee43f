// Command recording into a VkCommandBuffer; see VulkanDevice.h for the synchronisation model.
#pragma once
#include <atomic>
#include <array>
#include <vector>

#include "VulkanDevice.h"
#include "fe/gdi/CommandStream.h"
#include "fe/gdi/Validation.h"

namespace fe::vk {

class VulkanCommandList final : public gdi::CommandList {
public:
    VulkanCommandList(VulkanDevice& device, gdi::QueueKind queue);
    gdi::QueueKind queue() const override { return queue_; }
    bool madeBy(const VulkanDevice& d) const {
        return !orphaned_ && &dev_ == &d;
    }  // a new device may reuse the address
    ~VulkanCommandList() override;
    void orphan();  // the device's destructor, for a list that outlives it (LiveLists.h)

    void beginRenderPass(const gdi::RenderPassDesc& desc) override;
    // Every call that maps field for field to its record (CommandSet.inc).
#include "fe/gdi/CommandListOverrides.inc"
    void beginSecondary(const gdi::RenderPassDesc& pass) override;
    void endSecondary() override;
    void reset() override;
    void executeSecondary(std::span<gdi::CommandList* const> lists) override;
    uint64_t nativeCommandBuffer() override {
        ensureRecording("nativeCommandBuffer");
        return uint64_t(cb_);
    }

    // For the device: submit checks every list before it ends any (a refused submission leaves
    // each list as it was), then ends each recording.
    void checkSubmittable() const;
    const gdi::validate::QueryRecording& queries() const { return queries_; }
    VkCommandBuffer finish();
    void submitted(gdi::FenceValue value);
    static void fullBarrier(VkCommandBuffer cb);
    static void toGeneral(VkCommandBuffer cb, VkImage image,
                          gdi::Format format);  // every subresource
    void barrier(const gdi::TextureBarrier* barriers, uint32_t count) override;
    void barrier(const gdi::BufferBarrier* barriers, uint32_t count) override;

private:
    // Lookups that note what the recording uses, so submit can refuse objects destroyed since.
    enum class UsedKind : uint32_t { Buffer, Texture, Sampler, Pipeline, Timer, QuerySet };
    // State bound before the recording's first native command counts as recording too: an
    // object bound, then destroyed, must outlive the draws that will still name it natively.
    void note(UsedKind kind, uint32_t id) {
        if (openSince_ == kNotOpen) [[unlikely]]
            openRecording();
        used_.push_back(uint64_t(kind) << 32 | id);
    }
    // Per-object binds repeat one buffer at many offsets: a buffer is noted when it differs
    // from the last one noted (one compare on the per-draw path, measured in docs/MEASUREMENT_LOG.md).
    void noteBuffer(uint32_t id) {
        if (id != lastBuffer_) [[unlikely]]
            note(UsedKind::Buffer, lastBuffer_ = id);
    }
    Buffer& usedBuffer(gdi::BufferHandle h) {
        Buffer& b = dev_.buffer(h);
        noteBuffer(h.id);
        return b;
    }
    Texture& usedTexture(gdi::TextureHandle h) {
        Texture& t = dev_.texture(h);
        note(UsedKind::Texture, h.id);
        return t;
    }
    // Copies, mips, discards and barriers address the texture itself, never a view of it.
    Texture& copiedTexture(gdi::TextureHandle h) {
        Texture& t = usedTexture(h);
        gdi::validate::notAView(t.viewOf != 0, t.name, "copy, mip generation or barrier");
        return t;
    }
    Sampler& usedSampler(gdi::SamplerHandle h) {
        Sampler& s = dev_.sampler(h);
        note(UsedKind::Sampler, h.id);
        return s;
    }
    Pipeline& usedPipeline(gdi::PipelineHandle h) {
        Pipeline& p = dev_.pipeline(h);
        note(UsedKind::Pipeline, h.id);
        return p;
    }
    Timer& usedTimer(gdi::TimerHandle h) {
        Timer& t = dev_.timer(h);
        note(UsedKind::Timer, h.id);
        return t;
    }
    QuerySet& usedQuerySet(gdi::QuerySetHandle h, const char* what);
    void checkAlive() const;
    struct PassTextures {
        std::vector<Texture*> colors, resolve;
        Texture* depth = nullptr;
        Texture* depthResolve = nullptr;
    };
    gdi::validate::PassSignature checkPass(const gdi::RenderPassDesc& desc, PassTextures* textures);
    void unbindAll();
    void clearRecording();
    // Calls refused in a pass of secondary lists and after endSecondary: one flag on their path.
    void checkUnrestricted(const char* what) const {
        if (restricted_) [[unlikely]]
            restrictedCall(what);
    }
    [[noreturn, gnu::cold, gnu::noinline]] void restrictedCall(const char* what) const;
    void releaseNative();  // command pools and secondary buffers back to the device
    void addRecordingBuffer();
    void hostReadable(const Buffer& b);
    // `what`: the call, named in the Error of a list whose device was destroyed.
    void ensureRecording(const char* what) {
        if (!recording_) [[unlikely]]
            beginRecording(what);
    }
    void beginRecording(const char* what);
    // A list whose device was destroyed (orphan()) throws at every call, naming it, before it
    // touches the device; the per-draw paths reach this through their not-ready branch.
    void checkDevice(const char* what) const {
        if (orphaned_) [[unlikely]]
            gdi::validate::listOfDestroyedDevice(what);
    }
    void outsidePass(const char* what);
    void barrierIfWritten();
    void pushDirty(uint64_t push, VkPipelineBindPoint bindPoint);
    void pushGathered(uint64_t push);
    const Buffer& indirectArgs(gdi::BufferHandle h, uint64_t offset, uint32_t drawCount,
                               uint32_t stride, uint32_t recordSize, const char* what);
    const Buffer& countBuffer(gdi::BufferHandle h, uint64_t offset, const char* what);
    void indexedIndirect(const char* what) const;
    [[noreturn, gnu::cold, gnu::noinline]] void badBindings() const;
    // A slot's kind: its descriptor type, and for textures 1 + TextureDimension in the top byte.
    static uint32_t kindCode(VkDescriptorType type, uint8_t dimension = 0) {
        return uint32_t(type) | uint32_t(dimension) << 24;
    }
    // The slot holds exactly what the pipeline declares (one compare per pushed slot); when not,
    // slotAcceptable decides: a slot no shader gives a texture kind takes any kind of texture.
    bool slotMatches(uint32_t slot) const { return bindings_[slot].kind == expectedKinds_[slot]; }
    bool slotAcceptable(uint32_t slot) const {
        const uint32_t bound = bindings_[slot].kind, expected = expectedKinds_[slot];
        return (bound & 0xFFFFFFu) == (expected & 0xFFFFFFu) &&
               (!(expected >> 24) || bound == expected);
    }
    void checkSlots(uint64_t slots) const {
        for (; slots; slots &= slots - 1)
            if (!slotAcceptable(uint32_t(std::countr_zero(slots)))) badBindings();
    }
    // Feedback loops (validate::FeedbackLoops): a slot that the bound pipeline may not read
    // (its texture reaches an attachment of the open pass) carries kFeedback in its descriptor
    // type, so the draw's one kind comparison fails and badBindings names the loop. Which slots
    // carry it is refreshed when a texture, pass or pipeline changes (read-only depth depends
    // on the pipeline), never per draw.
    static constexpr uint32_t kFeedback = 1u << 23;
    static bool holdsTexture(uint32_t kind) {
        const uint32_t type = kind & 0xFFFFFFu & ~kFeedback;
        return type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER ||
               type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    }
    void refreshFeedback();
    void beginPassFeedback(const gdi::RenderPassDesc& desc);
    void endPassFeedback();
    // readyToDraw_ and, for draw()'s one comparison, the vertices it may reach: -1 when not ready,
    // so that every draw takes the checked path, which names the problem.
    void updateReadyToDraw() {
        readyToDraw_ = inPass_ && pipeline_ && !computeBound_ && vertexInputs_.ready();
        drawVertexLimit_ =
            readyToDraw_ ? int64_t(std::min<uint64_t>(vertexInputs_.vertexCapacity(), INT64_MAX))
                         : -1;
    }
    void setNotReady() { readyToDraw_ = false, drawVertexLimit_ = -1; }
    [[noreturn, gnu::cold, gnu::noinline]] void drawRefused(uint32_t vertexCount,
                                                            uint32_t instanceCount,
                                                            uint32_t firstVertex,
                                                            uint32_t firstInstance) const;
    [[noreturn, gnu::cold, gnu::noinline]] void notReadyToDraw(const char* what) const;
    [[gnu::noinline]] void pushValidatedSlot(uint32_t slot);
    [[gnu::noinline]] void drawPushing(uint32_t vertexCount, uint32_t instanceCount,
                                       uint32_t firstVertex, uint32_t firstInstance);
    // Buffer binding: a branch-free leaf fast path per setter; anything unusual (not recording,
    // size 0 = "the rest", any invalid argument) goes to the checked path, which gives the error.
    template <VkDescriptorType kType>
    void setBuffer(uint32_t slot, gdi::BufferHandle buffer, uint64_t offset, uint64_t size);
    template <VkDescriptorType kType>
    [[gnu::noinline]] void setBufferChecked(uint32_t slot, gdi::BufferHandle buffer,
                                            uint64_t offset, uint64_t size);
    void bindBuffer(uint32_t slot, VkDescriptorType type, VkBuffer buffer, uint64_t offset,
                    uint64_t size) {
        bindings_[slot].kind = type;
        bindings_[slot].buffer = {buffer, offset, size};
        dirtySlots_ |= uint64_t(1) << slot;
    }
    void checkRanges(uint64_t slots) const;  // validation mode, the slots a draw pushes
    // An unbound slot has type kUnbound, so the one type check before a push also catches a
    // missing binding (no separate bound-slot mask to maintain per bind).
    static constexpr uint32_t kUnbound = VK_DESCRIPTOR_TYPE_MAX_ENUM;
    struct Binding {
        uint32_t kind = kUnbound;  // kindCode, checked against the pipeline's before a push
        VkDescriptorBufferInfo buffer;
        VkDescriptorImageInfo image;
        uint64_t pad;  // 64 bytes: a slot's address is one shift away
    };

    VulkanDevice& dev_;
    const gdi::QueueKind queue_;  // what it may record (validate::queueAllows), its pools' family
    const bool validating_;       // DeviceFeatures::validation: buffer ranges against blocks
    const gdi::validate::BindingLimits uniformLimits_, storageLimits_;
    const gdi::validate::ViewportLimits viewportLimits_;
    struct RecordingBuffer {
        VkCommandPool pool = VK_NULL_HANDLE;
        VkCommandBuffer cb = VK_NULL_HANDLE;
        gdi::FenceValue fence = 0;  // of its last submission; 0: never submitted
    };
    std::vector<RecordingBuffer> buffers_;
    size_t current_ = 0;
    VkCommandBuffer cb_ = VK_NULL_HANDLE;  // buffers_[current_].cb
    std::vector<uint64_t> used_;           // UsedKind << 32 | handle id, per use
    uint32_t lastBuffer_ = 0;              // the buffer noted last (0: none yet this recording)
    // Per kind (uniform, storage): the last buffer the checked path passed, as it was then. While
    // no object has been destroyed since (the device's destroy epoch), a bind of the same handle
    // takes its size and VkBuffer from here instead of looking the handle up again.
    struct BoundBuffer {
        uint32_t id = 0;  // 0 (no handle): size 0 sends every bind to the checked path
        uint64_t destroyEpoch = 0;
        VkBuffer buffer = VK_NULL_HANDLE;
        uint64_t size = 0;
    };
    std::array<BoundBuffer, 2> lastBound_{};
    uint64_t destroyEpoch_ = 0;
    static constexpr uint64_t kNotOpen = ~0ull;
    uint64_t openSince_ = kNotOpen;  // the destroy epoch this open recording registered, if any
    void openRecording();
    void closeRecording();
    bool recording_ = false;
    bool inPass_ = false;
    // Dynamic state the pass has set (setBlendConstant, ...): setPipeline leaves it (Device.h).
    static constexpr uint8_t kBlendConstantSet = 1, kStencilReferenceSet = 2, kDepthBiasSet = 4;
    uint8_t dynamicSet_ = 0;
    bool passHasLabel_ = false;
    bool written_ = false;  // a command since the last barrier wrote memory
    bool automaticBarriers_ = true;
    gdi::FenceValue lastSubmit_ = 0;
    Pipeline* pipeline_ = nullptr;
    bool computeBound_ = false;  // pipeline_ is a compute pipeline (draws are errors)
    bool readyToDraw_ = false;
    int64_t drawVertexLimit_ = -1;  // updateReadyToDraw
    bool orphaned_ =
        false;  // the device was destroyed first (orphan())   // in a render pass with a graphics pipeline: the one per-draw state check
    uint64_t requiredSlots_ = 0;      // pipeline_->requiredSlots, kept here for the per-draw path
    std::array<uint32_t, 4> draw_{};  // draw arguments while the draw pushes descriptors
    VkPipelineLayout layout_ = VK_NULL_HANDLE;  // pipeline_->layout
    PFN_vkCmdPushDescriptorSetKHR pushDescriptorSet_ = nullptr;
    gdi::Rect renderArea_;
    uint32_t passSamples_ = 1;  // sample count of the open pass's attachments
    std::array<uint32_t, 64>
        expectedKinds_{};  // per slot the pipeline uses: its kindCode (set with writes_)
    gdi::validate::VertexInputs vertexInputs_;  // vertex and index buffers, checked at each draw
    std::array<Binding, 64> bindings_{};
    // Descriptor writes for the pipeline with handle id writesFor_ (prepared by setPipeline), each pointing
    // at its slot in bindings_.
    std::array<VkWriteDescriptorSet, 64> writes_{};
    uint32_t writesFor_ = 0;
    // Slots set since they were last pushed. Push descriptors may be updated incrementally
    // until a pipeline with another layout disturbs the set, which makes every slot dirty.
    uint64_t dirtySlots_ = ~uint64_t(0);
    // Per kind (uniform, storage): the slots where the bound pipeline declares a buffer of that
    // kind. The per-object bind of the last buffer pushes such a slot at once, as a program
    // calling Vulkan itself would, so the draw after it has nothing to push (no register spills
    // around a call).
    std::array<uint64_t, 2> eagerSlots_{};
    VkPipelineBindPoint bindPoint_ = VK_PIPELINE_BIND_POINT_GRAPHICS;  // pipeline_->bindPoint
    int debugDepth_ = 0;
    gdi::validate::QueryRecording queries_;
    std::array<std::byte, gdi::kMaxConstantBytes>
        constants_{};  // setConstants' bytes, pushed at setPipeline
    // Secondary lists (Device.h): this list records one (secondary_, until executed; ended_
    // after endSecondary), or its open pass takes them (secondaryPass_).
    bool secondary_ = false, ended_ = false, secondaryPass_ = false, restricted_ = false;
    gdi::validate::PassSignature
        signature_;  // of the open pass, or the pass a secondary list is for
    // A recorded secondary command buffer, shared by the list that recorded it and every primary
    // that executed it; back to the device, after the last submission that ran it, when the
    // last of them lets go (a secondary list is executed any number of times).
    struct SharedSecondary {
        SharedSecondary(VulkanDevice& d, const VulkanDevice::SecondaryRecording& r)
            : dev(d), recording(r) {}  // (clang 15 has no aggregate make_shared)
        VulkanDevice& dev;
        VulkanDevice::SecondaryRecording recording;
        std::atomic<gdi::FenceValue> lastFence{0};
        ~SharedSecondary();
    };
    std::shared_ptr<SharedSecondary> lease_;  // the secondary command buffer this list records
    std::vector<std::shared_ptr<SharedSecondary>> executed_;  // held until this list's submission
    // A pass of secondary lists is a chain of suspended and resumed render pass instances (the
    // primary's own draws inline, each executeSecondary in one of its own): what they share.
    struct PassInstance {
        std::vector<VkRenderingAttachmentInfo> colors;
        VkRenderingAttachmentInfo depth{}, stencil{};
        VkRenderingInfo info{};
        void begin(VkCommandBuffer cb, VkRenderingFlags flags);
    } passInstance_;
    gdi::validate::FeedbackLoops feedback_;  // last: keeps it off the per-draw members' cache lines
};

}  // namespace fe::vk
