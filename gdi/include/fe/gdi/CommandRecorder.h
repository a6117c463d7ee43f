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

    FE_CMD_TYPE_NAMES
    // The calls that map field for field to a record, generated from the command set: each goes
    // to the inner list, then (if it did not throw) becomes its record.
#define FE_FIELD(Type, name) (Type, name)
#define FE_COMMAND(Name, Fields)
#define FE_CALL(Name, method, Fields)                    \
    void method(FE_CMD_PARAMS(Fields)) override {        \
        check<cmd::Name>(FE_CMD_ARGS(Fields));           \
        inner_->method(FE_CMD_ARGS(Fields));             \
        stream_->record<cmd::Name>(FE_CMD_ARGS(Fields)); \
    }
#include "fe/gdi/CommandSet.inc"
#undef FE_CALL
#undef FE_COMMAND
#undef FE_FIELD
    // The rest, by hand.
    void beginRenderPass(const RenderPassDesc& desc) override;
    void barrier(const TextureBarrier* barriers, uint32_t count) override;
    void barrier(const BufferBarrier* barriers, uint32_t count) override;
    void beginSecondary(const RenderPassDesc& pass) override;
    void endSecondary() override;
    void reset() override;
    void executeSecondary(std::span<CommandList* const> lists) override;
    QueueKind queue() const override { return inner_->queue(); }
    using CommandList::barrier;
    using CommandList::executeSecondary;

private:
    // Checks of the recording device beyond the inner list's own: none but for buffer bindings.
    template <class R, class... A>
    void check(const A&...) {}
    template <class R>
    requires std::is_same_v<R, cmd::SetUniformBuffer> || std::is_same_v<R, cmd::SetStorageBuffer>
    void check(uint32_t slot, BufferHandle buffer, uint64_t offset, uint64_t size);
    template <class R, class T>
    void pushArray(std::span<const T> items);
    Device& device_;
    std::unique_ptr<CommandList> inner_;
    std::unique_ptr<cmd::CommandStream> stream_;
    std::shared_ptr<const cmd::CommandStream> recorded_;  // a secondary list's, after endSecondary
};

// Handle ids of the recording device -> the replaying device's. Ids missing from a map are
// used as they are when keepUnknown (right when both are one device), else they become an id no
// device has, so the replaying device refuses them (captures from files).
struct HandleMap {
    std::unordered_map<uint32_t, uint32_t> buffers, textures, samplers, pipelines, timers,
        querySets;
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
void applyStream(const cmd::CommandStream& stream, Device& device, CommandList& list,
                 const HandleMap& map = {}, ApplyObserver* observer = nullptr);

}  // namespace fe::gdi
