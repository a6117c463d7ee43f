#include "fe/gdi/CommandRecorder.h"
#include "fe/gdi/Validation.h"

#include <vector>

namespace fe::gdi {

RecordingCommandList::RecordingCommandList(Device& device, std::unique_ptr<CommandList> inner)
    : device_(device), inner_(std::move(inner)), stream_(std::make_unique<cmd::CommandStream>()) {}

std::unique_ptr<cmd::CommandStream> RecordingCommandList::takeStream() {
    return std::exchange(stream_, std::make_unique<cmd::CommandStream>());
}

// Each call reaches the device's list first: a mistake throws there and is not recorded.
void RecordingCommandList::beginRenderPass(const RenderPassDesc& d) {
    inner_->beginRenderPass(d);
    const size_t payload =
        cmd::CommandStream::payloadSize(d.colors.size() * sizeof(ColorAttachment)) +
        cmd::CommandStream::payloadSize(d.debugName);
    auto* r = stream_->push(
        cmd::BeginRenderPass{.depth = d.depth, .secondaryLists = d.secondaryLists}, payload);
    r->colors = stream_->payload(*r, std::span<const ColorAttachment>(d.colors));
    r->debugName = stream_->payload(*r, d.debugName);
}
// Offsets are checked against the recording device's limits too: a capture device reports the
// alignments every backend takes, stricter than its inner device's own.
template <class R>
requires std::is_same_v<R, cmd::SetUniformBuffer> || std::is_same_v<R, cmd::SetStorageBuffer>
void RecordingCommandList::check(uint32_t, BufferHandle, uint64_t offset, uint64_t size) {
    if constexpr (std::is_same_v<R, cmd::SetUniformBuffer>)
        validate::bindingLimits(offset, size, validate::uniformBindingLimits(device_.info().limits),
                                "setUniformBuffer");
    else
        validate::bindingLimits(offset, size, validate::storageBindingLimits(device_.info().limits),
                                "setStorageBuffer");
}
template void RecordingCommandList::check<cmd::SetUniformBuffer>(uint32_t, BufferHandle, uint64_t,
                                                                 uint64_t);
template void RecordingCommandList::check<cmd::SetStorageBuffer>(uint32_t, BufferHandle, uint64_t,
                                                                 uint64_t);
template <class R, class T>
void RecordingCommandList::pushArray(std::span<const T> items) {
    auto* r = stream_->push(R{}, cmd::CommandStream::payloadSize(items.size_bytes()));
    r->barriers = stream_->payload(*r, items);
}
void RecordingCommandList::barrier(const TextureBarrier* b, uint32_t n) {
    inner_->barrier(b, n), pushArray<cmd::TextureBarriers>(std::span(b, n));
}
void RecordingCommandList::barrier(const BufferBarrier* b, uint32_t n) {
    inner_->barrier(b, n), pushArray<cmd::BufferBarriers>(std::span(b, n));
}
// A secondary list's records go to its own stream, which the executing list adopts.
void RecordingCommandList::beginSecondary(const RenderPassDesc& pass) {
    inner_->beginSecondary(pass);
    recorded_.reset();  // recorded anew: primaries that executed the old one keep theirs
}
void RecordingCommandList::reset() {
    inner_->reset();
    stream_ = std::make_unique<cmd::CommandStream>();
    recorded_.reset();
}
void RecordingCommandList::endSecondary() {
    inner_->endSecondary();
    recorded_ = takeStream();  // shared by every primary that executes it
}
void RecordingCommandList::executeSecondary(std::span<CommandList* const> lists) {
    std::vector<RecordingCommandList*> recorded;
    std::vector<CommandList*> inner;
    for (CommandList* l : lists) {
        auto* r = dynamic_cast<RecordingCommandList*>(l);
        if (!r) throw Error("executeSecondary: a recording list executes recording lists only");
        recorded.push_back(r);
        inner.push_back(r->inner_.get());
    }
    inner_->executeSecondary(inner);
    for (RecordingCommandList* r : recorded)
        stream_->push(cmd::ExecuteSecondary{stream_->adopt(r->recorded_)});
}

namespace {

// One call per record, handles mapped: the replaying half of CommandSet.inc.
struct Applier {
    Device& device;
    CommandList& list;
    const HandleMap& map;
    const cmd::CommandStream& stream;
    RenderPassDesc pass;  // the open pass, for the secondary lists it executes
    ApplyObserver* observer = nullptr;

    uint32_t mapped(const std::unordered_map<uint32_t, uint32_t>& m, uint32_t id) const {
        if (id == 0) return 0;  // a null handle stays null
        const auto it = m.find(id);
        if (it != m.end()) return it->second;
        return map.keepUnknown ? id : HandleMap::kUnknownId;
    }
    BufferHandle operator[](BufferHandle h) const { return {mapped(map.buffers, h.id)}; }
    TextureHandle operator[](TextureHandle h) const { return {mapped(map.textures, h.id)}; }
    SamplerHandle operator[](SamplerHandle h) const { return {mapped(map.samplers, h.id)}; }
    PipelineHandle operator[](PipelineHandle h) const { return {mapped(map.pipelines, h.id)}; }
    TimerHandle operator[](TimerHandle h) const { return {mapped(map.timers, h.id)}; }
    QuerySetHandle operator[](QuerySetHandle h) const { return {mapped(map.querySets, h.id)}; }
    const Applier& m() const { return *this; }

    void operator()(const cmd::BeginRenderPass& r) {
        pass = {};
        for (ColorAttachment c : cmd::view(r, r.colors)) {
            c.texture = m()[c.texture], c.resolveTexture = m()[c.resolveTexture];
            pass.colors.push_back(c);
        }
        pass.depth = r.depth;
        pass.depth.texture = m()[r.depth.texture],
        pass.depth.resolveTexture = m()[r.depth.resolveTexture];
        pass.debugName = cmd::view(r, r.debugName);
        pass.secondaryLists = r.secondaryLists;
        if (observer) observer->adjustPass(pass);
        list.beginRenderPass(pass);
    }
    // A record's field as its call's argument: handles mapped, payloads viewed, the rest as is.
    template <class R, class T>
    static const T& arg(const R&, const T& value) {
        return value;
    }
    template <class R>
    BufferHandle arg(const R&, BufferHandle h) const {
        return m()[h];
    }
    template <class R>
    TextureHandle arg(const R&, TextureHandle h) const {
        return m()[h];
    }
    template <class R>
    SamplerHandle arg(const R&, SamplerHandle h) const {
        return m()[h];
    }
    template <class R>
    PipelineHandle arg(const R&, PipelineHandle h) const {
        return m()[h];
    }
    template <class R>
    TimerHandle arg(const R&, TimerHandle h) const {
        return m()[h];
    }
    template <class R>
    QuerySetHandle arg(const R&, QuerySetHandle h) const {
        return m()[h];
    }
    template <class R, class T>
    static std::span<const T> arg(const R& r, cmd::Array<T> a) {
        return cmd::view(r, a);
    }
    template <class R>
    static const char* arg(const R& r, cmd::String s) {
        return cmd::view(r, s);
    }

    FE_CMD_TYPE_NAMES
    // The calls that map field for field, generated from the command set.
#define FE_FIELD(Type, name) (Type, name)
#define FE_COMMAND(Name, Fields)
#define FE_CALL(Name, method, Fields)                      \
    void operator()([[maybe_unused]] const cmd::Name& r) { \
        list.method(FE_CMD_RECORD_ARGS(Fields));           \
    }
#include "fe/gdi/CommandSet.inc"
#undef FE_CALL
#undef FE_COMMAND
#undef FE_FIELD

    // The rest, by hand.
    void operator()(const cmd::TextureBarriers& r) {
        std::vector<TextureBarrier> b(cmd::view(r, r.barriers).begin(),
                                      cmd::view(r, r.barriers).end());
        for (TextureBarrier& x : b) x.texture = m()[x.texture];
        list.barrier(b.data(), uint32_t(b.size()));
    }
    void operator()(const cmd::BufferBarriers& r) {
        std::vector<BufferBarrier> b(cmd::view(r, r.barriers).begin(),
                                     cmd::view(r, r.barriers).end());
        for (BufferBarrier& x : b) x.buffer = m()[x.buffer];
        list.barrier(b.data(), uint32_t(b.size()));
    }
    // The GL backend's dense records are in no recorded stream (decodeCommandStream refuses them).
    void operator()(const cmd::DrawOneInstance&) { throw Error("replay: a GL backend record"); }
    void operator()(const cmd::SetUniformOffset&) { throw Error("replay: a GL backend record"); }
    void operator()(const cmd::ExecuteSecondary& r) {
        auto secondary = device.createCommandList();
        secondary->beginSecondary(pass);
        applyStream(stream.child(r.child), device, *secondary, map);
        secondary->endSecondary();
        list.executeSecondary(*secondary);  // the primary keeps what it runs: the list may go
    }
};

}  // namespace

void applyStream(const cmd::CommandStream& stream, Device& device, CommandList& list,
                 const HandleMap& map, ApplyObserver* observer) {
    Applier a{device, list, map, stream, {}, observer};
    if (!observer) {
        stream.forEach([&](const auto& record) { a(record); });
        return;
    }
    stream.forEachRaw([&](std::span<const std::byte> raw) {
        if (observer->stop) return;
        const cmd::Op op = reinterpret_cast<const cmd::CommandStream::Header*>(raw.data())->op;
        const std::byte* record = raw.data() + sizeof(cmd::CommandStream::Header);
        if (!observer->before(op, record, list)) return;
        cmd::CommandStream::dispatch(op, record, a);
        observer->after(op, record, list);
    });
}

}  // namespace fe::gdi
