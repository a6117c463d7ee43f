// Command recording for GL: each call is validated as on Vulkan (same checks, same messages,
// thrown where the mistake is made) and encoded into a CommandStream; nothing touches GL.
// Device::submit hands the stream to the context thread, which replays it (GlReplay.h).
// Recording may therefore run on any thread, several lists at once.
#pragma once
#include <array>
#include <memory>

#include "fe/gdi/CommandStream.h"
#include "fe/gdi/Validation.h"
#include "gl/GlDevice.h"

namespace fe::gl {

class GlCommandList final : public gdi::CommandList {
public:
    GlCommandList(GlDevice& d, gdi::QueueKind queue);
    gdi::QueueKind queue() const override { return queue_; }
    bool madeBy(const GlDevice& d) const {
        return !orphaned_ && &dev_ == &d;
    }  // a new device may reuse the address
    ~GlCommandList() override;
    void orphan();  // the device's destructor, for a list that outlives it (LiveLists.h)

    void beginRenderPass(const gdi::RenderPassDesc& desc) override;
    // Every call that maps field for field to its record (CommandSet.inc).
#include "fe/gdi/CommandListOverrides.inc"
    const gdi::validate::QueryRecording& queries() const { return queries_; }
    void barrier(const gdi::TextureBarrier* barriers, uint32_t count) override;
    void barrier(const gdi::BufferBarrier* barriers, uint32_t count) override;
    void beginSecondary(const gdi::RenderPassDesc& pass) override;
    void endSecondary() override;
    void reset() override;
    void executeSecondary(std::span<gdi::CommandList* const> lists) override;

    // For Device::submit, which checks every list before it takes any (a refused submission
    // leaves each list as it was): the recording is complete and no object it uses was
    // destroyed since; then finish() hands over the stream and starts a new recording.
    void checkSubmittable() const;
    std::unique_ptr<gdi::cmd::CommandStream> finish();

private:
    gdi::validate::PassSignature checkPass(const gdi::RenderPassDesc& desc) const;
    // Calls refused in a pass of secondary lists and after endSecondary: one flag on their path.
    void checkUnrestricted(const char* what) const {
        if (restricted_) [[unlikely]]
            restrictedCall(what);
    }
    [[noreturn, gnu::cold, gnu::noinline]] void restrictedCall(const char* what) const;
    // A list whose device was destroyed (orphan()) throws at every call, naming it, before it
    // touches the device (calls that check `restricted_` or `outsidePass` get this from there).
    void checkDevice(const char* what) const {
        if (orphaned_) [[unlikely]]
            gdi::validate::listOfDestroyedDevice(what);
    }
    void outsidePass(const char* what) const;
    QuerySet& usedQuerySet(gdi::QuerySetHandle h, const char* what);
    // Copies, mips, discards and barriers address the texture itself, never a view of it.
    const Texture& copied(gdi::TextureHandle h) {
        const Texture& t = dev_.texture(h);
        gdi::validate::notAView(t.viewOf != 0, t.label, "copy, mip generation or barrier");
        return t;
    }
    void checkSlot(uint32_t slot, const char* what) const;
    template <gdi::BindingType kKind>
    void setBuffer(uint32_t slot, gdi::BufferHandle h, uint64_t offset, uint64_t size);
    template <gdi::BindingType kKind>
    [[gnu::noinline]] void setBufferChecked(uint32_t slot, gdi::BufferHandle h, uint64_t offset,
                                            uint64_t size);
    // Validation: the next draw checks the range bound at slot against the block (checkBindings).
    void noteRange(uint32_t slot, uint64_t bytes) {
        boundBytes_[slot] = bytes;
        unchecked_ |= uint64_t(1) << slot;
    }
    void bound(uint32_t slot, gdi::BindingType kind, uint8_t dimension = 0) {
        kinds_[slot] = uint8_t(1 + uint8_t(kind));
        dims_[slot] = dimension;
        unchecked_ |= uint64_t(1) << slot;
    }
    // A buffer bound where one of its kind already is (the per-object pattern) leaves the slot's
    // check as it was: a buffer kind never carries a dimension or kFeedback, so the draw would
    // compare the same values again (26 instructions a draw in fe_bench_abstraction).
    void boundBuffer(uint32_t slot, gdi::BindingType kind) {
        if (kinds_[slot] != uint8_t(1 + uint8_t(kind))) [[unlikely]]
            bound(slot, kind);
    }
    // Feedback loops (validate::FeedbackLoops): a slot whose texture reaches an attachment of the
    // open pass carries kFeedback in its kind, so slotMatches fails and checkEachSlot decides.
    static constexpr uint8_t kFeedback = 0x80;
    void beginPassFeedback(const gdi::RenderPassDesc& desc);
    void endPassFeedback();
    // The slot holds what the pipeline declares: its kind, and a texture of the shader's kind.
    bool slotMatches(uint32_t slot) const {
        return kinds_[slot] == pipeline_->slotKinds[slot] &&
               (!pipeline_->slotDimensions[slot] || dims_[slot] == pipeline_->slotDimensions[slot]);
    }
    void checkBindings();
    [[gnu::noinline]] void checkEachSlot(uint64_t check) const;
    [[noreturn, gnu::cold, gnu::noinline]] void notReadyToDraw(const char* what) const;
    void prepareDraw(const char* what) {
        if (!readyToDraw_) [[unlikely]]
            notReadyToDraw(what);
        if (unchecked_ & requiredSlots_) [[unlikely]]  // no call when no used slot changed
            checkBindings();
    }
    [[gnu::noinline]] void drawChecked(uint32_t vertexCount, uint32_t instanceCount,
                                       uint32_t firstVertex, uint32_t firstInstance);
    void prepareCompute(const char* what);
    void indirectArgs(gdi::BufferHandle h, uint64_t offset, uint32_t drawCount, uint32_t stride,
                      uint32_t recordSize, const char* what);
    void countBuffer(gdi::BufferHandle h, uint64_t offset, const char* what) const;
    void restart();    // a new recording
    void unbindAll();  // no pipeline, bindings or index buffer
    // A record whose one field is an array payload (the barrier commands).
    template <class Record, class T>
    void pushArray(std::span<const T> items) {
        auto* r = stream_->push(Record{}, gdi::cmd::CommandStream::payloadSize(items.size_bytes()));
        r->barriers = stream_->payload(*r, items);
    }

    GlDevice& dev_;
    const gdi::QueueKind queue_;  // what it may record (validate::queueAllows)
    const bool validating_;       // DeviceFeatures::validation: buffer ranges against blocks
    std::array<uint64_t, 64> boundBytes_{};  // per slot, the buffer range bound (validation)
    const gdi::validate::BindingLimits uniformLimits_, storageLimits_;
    const gdi::validate::ViewportLimits viewportLimits_;
    std::unique_ptr<gdi::cmd::CommandStream> stream_;
    // A secondary list's recording after endSecondary, shared with the primaries executing it.
    std::shared_ptr<const gdi::cmd::CommandStream> recorded_;
    uint64_t destroyEpoch_ = 0;  // the device's destroy count when this recording began
    bool inPass_ = false;
    int depth_ = 0;
    uint32_t passSamples_ = 1;  // sample count of the open pass's attachments
    const Pipeline* pipeline_ = nullptr;
    bool readyToDraw_ = false;         // in a render pass with a graphics pipeline
    bool orphaned_ = false;            // the device was destroyed first (orphan())
    uint64_t requiredSlots_ = 0;       // pipeline_->requiredSlots
    std::array<uint8_t, 64> kinds_{};  // per slot: 1 + BindingType bound, 0 = unbound
    std::array<uint8_t, 64>
        dims_{};  // per slot: 1 + TextureDimension of the bound texture, 0 = a buffer
    uint64_t unchecked_ = ~uint64_t(0);         // slots to check at the next draw/dispatch
    gdi::validate::VertexInputs vertexInputs_;  // vertex and index buffers, checked at each draw
    gdi::validate::FeedbackLoops feedback_;
    // Per kind (uniform, storage): the last buffer the checked path bound (setBuffer).
    struct BoundBuffer {
        uint32_t id = 0;
        uint64_t destroyEpoch = 0;  // the device's destroy count before it was looked up
        uint64_t size = 0;
    };
    std::array<BoundBuffer, 2> lastBound_{};
    // The stream's last SetUniformBuffer record since the recording or the last executeSecondary
    // began: a bind that repeats its slot, buffer and size is recorded as SetUniformOffset.
    struct LastUniform {
        uint32_t slot = ~0u;
        uint32_t id = 0;
        uint64_t size = 0;
    };
    LastUniform lastUniform_;
    // Secondary lists (Device.h): this list records one (secondary_, until executed; ended_
    // after endSecondary), or its open pass takes them (secondaryPass_).
    bool secondary_ = false, ended_ = false, secondaryPass_ = false, restricted_ = false;
    gdi::validate::PassSignature
        signature_;  // of the open pass, or the pass a secondary list is for
    gdi::validate::QueryRecording queries_;
};

}  // namespace fe::gl
