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
    const size_t payload = cmd::CommandStream::payloadSize(d.colors.size() * sizeof(ColorAttachment)) +
                           cmd::CommandStream::payloadSize(d.debugName);
    auto* r = stream_->push(cmd::BeginRenderPass{.depth = d.depth, .secondaryLists = d.secondaryLists}, payload);
    r->colors = stream_->payload(*r, std::span<const ColorAttachment>(d.colors));
    r->debugName = stream_->payload(*r, d.debugName);
}
void RecordingCommandList::endRenderPass() { inner_->endRenderPass(), stream_->push(cmd::EndRenderPass{}); }
void RecordingCommandList::setPipeline(PipelineHandle p) { inner_->setPipeline(p), stream_->push(cmd::SetPipeline{p}); }
void RecordingCommandList::setViewport(const Viewport& v) { inner_->setViewport(v), stream_->push(cmd::SetViewport{v}); }
void RecordingCommandList::setScissor(const Rect& r) { inner_->setScissor(r), stream_->push(cmd::SetScissor{r}); }
void RecordingCommandList::setBlendConstant(const std::array<float, 4>& c) {
    inner_->setBlendConstant(c), stream_->push(cmd::SetBlendConstant{c});
}
void RecordingCommandList::setStencilReference(uint8_t v) { inner_->setStencilReference(v), stream_->push(cmd::SetStencilReference{v}); }
void RecordingCommandList::setDepthBias(float c, float s, float k) { inner_->setDepthBias(c, s, k), stream_->push(cmd::SetDepthBias{c, s, k}); }
void RecordingCommandList::setConstants(uint32_t offset, ByteSpan data) {
    inner_->setConstants(offset, data);
    auto* r = stream_->push(cmd::SetConstants{offset}, cmd::CommandStream::payloadSize(data.size()));
    r->data = stream_->payload(*r, data);
}
void RecordingCommandList::setVertexBuffer(uint32_t i, BufferHandle b, uint64_t o) {
    inner_->setVertexBuffer(i, b, o), stream_->push(cmd::SetVertexBuffer{i, b, o});
}
void RecordingCommandList::setIndexBuffer(BufferHandle b, IndexType t, uint64_t o) {
    inner_->setIndexBuffer(b, t, o), stream_->push(cmd::SetIndexBuffer{b, t, o});
}
// Offsets are checked against the recording device's limits too: a capture device reports the
// alignments every backend takes, stricter than its inner device's own.
void RecordingCommandList::setUniformBuffer(uint32_t s, BufferHandle b, uint64_t o, uint64_t n) {
    validate::bindingLimits(o, n, validate::uniformBindingLimits(device_.info().limits), "setUniformBuffer");
    inner_->setUniformBuffer(s, b, o, n), stream_->push(cmd::SetUniformBuffer{s, b, o, n});
}
void RecordingCommandList::setStorageBuffer(uint32_t s, BufferHandle b, uint64_t o, uint64_t n) {
    validate::bindingLimits(o, n, validate::storageBindingLimits(device_.info().limits), "setStorageBuffer");
    inner_->setStorageBuffer(s, b, o, n), stream_->push(cmd::SetStorageBuffer{s, b, o, n});
}
void RecordingCommandList::setTexture(uint32_t s, TextureHandle t, SamplerHandle p) {
    inner_->setTexture(s, t, p), stream_->push(cmd::SetTexture{s, t, p});
}
void RecordingCommandList::setStorageTexture(uint32_t s, TextureHandle t, uint32_t m) {
    inner_->setStorageTexture(s, t, m), stream_->push(cmd::SetStorageTexture{s, t, m});
}
void RecordingCommandList::draw(uint32_t v, uint32_t i, uint32_t fv, uint32_t fi) {
    inner_->draw(v, i, fv, fi), stream_->push(cmd::Draw{v, i, fv, fi});
}
void RecordingCommandList::drawIndexed(uint32_t n, uint32_t i, uint32_t f, int32_t b, uint32_t fi) {
    inner_->drawIndexed(n, i, f, b, fi), stream_->push(cmd::DrawIndexed{n, i, f, b, fi});
}
void RecordingCommandList::dispatch(uint32_t x, uint32_t y, uint32_t z) { inner_->dispatch(x, y, z), stream_->push(cmd::Dispatch{x, y, z}); }
void RecordingCommandList::drawIndirect(BufferHandle a, uint64_t o, uint32_t n, uint32_t s) {
    inner_->drawIndirect(a, o, n, s), stream_->push(cmd::DrawIndirect{a, o, n, s});
}
void RecordingCommandList::drawIndexedIndirect(BufferHandle a, uint64_t o, uint32_t n, uint32_t s) {
    inner_->drawIndexedIndirect(a, o, n, s), stream_->push(cmd::DrawIndexedIndirect{a, o, n, s});
}
void RecordingCommandList::drawIndirectCount(BufferHandle a, uint64_t o, BufferHandle c, uint64_t co, uint32_t m, uint32_t s) {
    inner_->drawIndirectCount(a, o, c, co, m, s), stream_->push(cmd::DrawIndirectCount{a, o, c, co, m, s});
}
void RecordingCommandList::drawIndexedIndirectCount(BufferHandle a, uint64_t o, BufferHandle c, uint64_t co, uint32_t m,
                                                    uint32_t s) {
    inner_->drawIndexedIndirectCount(a, o, c, co, m, s), stream_->push(cmd::DrawIndexedIndirectCount{a, o, c, co, m, s});
}
void RecordingCommandList::dispatchIndirect(BufferHandle a, uint64_t o) {
    inner_->dispatchIndirect(a, o), stream_->push(cmd::DispatchIndirect{a, o});
}
void RecordingCommandList::generateMips(TextureHandle t) { inner_->generateMips(t), stream_->push(cmd::GenerateMips{t}); }
void RecordingCommandList::copyBuffer(BufferHandle d, uint64_t dO, BufferHandle s, uint64_t sO, uint64_t n) {
    inner_->copyBuffer(d, dO, s, sO, n), stream_->push(cmd::CopyBuffer{d, dO, s, sO, n});
}
void RecordingCommandList::clearBuffer(BufferHandle b, uint64_t o, uint64_t n, uint32_t v) {
    inner_->clearBuffer(b, o, n, v), stream_->push(cmd::ClearBuffer{b, o, n, v});
}
void RecordingCommandList::copyTexture(TextureHandle d, TextureHandle s, uint32_t m) {
    inner_->copyTexture(d, s, m), stream_->push(cmd::CopyTexture{d, s, m});
}
void RecordingCommandList::copyBufferToTexture(TextureHandle d, Subresource at, BufferHandle s, uint64_t o) {
    inner_->copyBufferToTexture(d, at, s, o), stream_->push(cmd::CopyBufferToTexture{d, at, s, o});
}
void RecordingCommandList::copyTextureToBuffer(BufferHandle d, uint64_t o, TextureHandle s, Subresource at) {
    inner_->copyTextureToBuffer(d, o, s, at), stream_->push(cmd::CopyTextureToBuffer{d, o, s, at});
}
void RecordingCommandList::copyBufferToTexture(TextureHandle d, const TextureRegion& r, BufferHandle s, const TexelLayout& l) {
    inner_->copyBufferToTexture(d, r, s, l), stream_->push(cmd::CopyBufferToTextureRegion{d, r, s, l});
}
void RecordingCommandList::copyTextureToBuffer(BufferHandle d, const TexelLayout& l, TextureHandle s, const TextureRegion& r) {
    inner_->copyTextureToBuffer(d, l, s, r), stream_->push(cmd::CopyTextureToBufferRegion{d, l, s, r});
}
void RecordingCommandList::copyTexture(TextureHandle d, const TextureRegion& at, TextureHandle s, const TextureRegion& r) {
    inner_->copyTexture(d, at, s, r), stream_->push(cmd::CopyTextureRegion{d, at, s, r});
}
void RecordingCommandList::beginTimer(TimerHandle t) { inner_->beginTimer(t), stream_->push(cmd::BeginTimer{t}); }
void RecordingCommandList::endTimer(TimerHandle t) { inner_->endTimer(t), stream_->push(cmd::EndTimer{t}); }
void RecordingCommandList::beginQuery(QuerySetHandle q, uint32_t i) { inner_->beginQuery(q, i), stream_->push(cmd::BeginQuery{q, i}); }
void RecordingCommandList::endQuery(QuerySetHandle q, uint32_t i) { inner_->endQuery(q, i), stream_->push(cmd::EndQuery{q, i}); }
void RecordingCommandList::writeTimestamp(QuerySetHandle q, uint32_t i) {
    inner_->writeTimestamp(q, i), stream_->push(cmd::WriteTimestamp{q, i});
}
void RecordingCommandList::resolveQueries(QuerySetHandle q, uint32_t f, uint32_t n, BufferHandle d, uint64_t o) {
    inner_->resolveQueries(q, f, n, d, o), stream_->push(cmd::ResolveQueries{q, f, n, d, o});
}
void RecordingCommandList::pushName(const char* name, bool label) {
    const char* text = name ? name : "";
    if (label) {
        auto* r = stream_->push(cmd::InsertDebugLabel{}, cmd::CommandStream::payloadSize(text));
        r->name = stream_->payload(*r, text);
    } else {
        auto* r = stream_->push(cmd::PushDebugGroup{}, cmd::CommandStream::payloadSize(text));
        r->name = stream_->payload(*r, text);
    }
}
void RecordingCommandList::pushDebugGroup(const char* name) { inner_->pushDebugGroup(name), pushName(name, false); }
void RecordingCommandList::popDebugGroup() { inner_->popDebugGroup(), stream_->push(cmd::PopDebugGroup{}); }
void RecordingCommandList::insertDebugLabel(const char* name) { inner_->insertDebugLabel(name), pushName(name, true); }
void RecordingCommandList::discardTexture(TextureHandle t) { inner_->discardTexture(t), stream_->push(cmd::DiscardTexture{t}); }
void RecordingCommandList::setAutomaticBarriers(bool e) { inner_->setAutomaticBarriers(e), stream_->push(cmd::SetAutomaticBarriers{e}); }
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
void RecordingCommandList::beginSecondary(const RenderPassDesc& pass) { inner_->beginSecondary(pass); }
void RecordingCommandList::endSecondary() { inner_->endSecondary(); }
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
    for (RecordingCommandList* r : recorded) stream_->push(cmd::ExecuteSecondary{stream_->adopt(r->takeStream())});
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
        pass.depth.texture = m()[r.depth.texture], pass.depth.resolveTexture = m()[r.depth.resolveTexture];
        pass.debugName = cmd::view(r, r.debugName);
        pass.secondaryLists = r.secondaryLists;
        if (observer) observer->adjustPass(pass);
        list.beginRenderPass(pass);
    }
    void operator()(const cmd::EndRenderPass&) { list.endRenderPass(); }
    void operator()(const cmd::SetPipeline& r) { list.setPipeline(m()[r.pipeline]); }
    void operator()(const cmd::SetViewport& r) { list.setViewport(r.viewport); }
    void operator()(const cmd::SetScissor& r) { list.setScissor(r.rect); }
    void operator()(const cmd::SetBlendConstant& r) { list.setBlendConstant(r.rgba); }
    void operator()(const cmd::SetStencilReference& r) { list.setStencilReference(r.reference); }
    void operator()(const cmd::SetDepthBias& r) { list.setDepthBias(r.constant, r.slope, r.clamp); }
    void operator()(const cmd::SetConstants& r) { list.setConstants(r.offset, cmd::view(r, r.data)); }
    void operator()(const cmd::SetVertexBuffer& r) { list.setVertexBuffer(r.index, m()[r.buffer], r.offset); }
    void operator()(const cmd::SetIndexBuffer& r) { list.setIndexBuffer(m()[r.buffer], r.type, r.offset); }
    void operator()(const cmd::SetUniformBuffer& r) { list.setUniformBuffer(r.slot, m()[r.buffer], r.offset, r.size); }
    void operator()(const cmd::SetStorageBuffer& r) { list.setStorageBuffer(r.slot, m()[r.buffer], r.offset, r.size); }
    void operator()(const cmd::SetTexture& r) { list.setTexture(r.slot, m()[r.texture], m()[r.sampler]); }
    void operator()(const cmd::SetStorageTexture& r) { list.setStorageTexture(r.slot, m()[r.texture], r.mipLevel); }
    void operator()(const cmd::Draw& r) { list.draw(r.vertexCount, r.instanceCount, r.firstVertex, r.firstInstance); }
    void operator()(const cmd::DrawIndexed& r) {
        list.drawIndexed(r.indexCount, r.instanceCount, r.firstIndex, r.baseVertex, r.firstInstance);
    }
    void operator()(const cmd::Dispatch& r) { list.dispatch(r.groupsX, r.groupsY, r.groupsZ); }
    void operator()(const cmd::DrawIndirect& r) { list.drawIndirect(m()[r.args], r.offset, r.drawCount, r.stride); }
    void operator()(const cmd::DrawIndexedIndirect& r) { list.drawIndexedIndirect(m()[r.args], r.offset, r.drawCount, r.stride); }
    void operator()(const cmd::DrawIndirectCount& r) {
        list.drawIndirectCount(m()[r.args], r.offset, m()[r.countBuffer], r.countOffset, r.maxDrawCount, r.stride);
    }
    void operator()(const cmd::DrawIndexedIndirectCount& r) {
        list.drawIndexedIndirectCount(m()[r.args], r.offset, m()[r.countBuffer], r.countOffset, r.maxDrawCount, r.stride);
    }
    void operator()(const cmd::DispatchIndirect& r) { list.dispatchIndirect(m()[r.args], r.offset); }
    void operator()(const cmd::GenerateMips& r) { list.generateMips(m()[r.texture]); }
    void operator()(const cmd::CopyBuffer& r) { list.copyBuffer(m()[r.dst], r.dstOffset, m()[r.src], r.srcOffset, r.size); }
    void operator()(const cmd::CopyTexture& r) { list.copyTexture(m()[r.dst], m()[r.src], r.mipLevel); }
    void operator()(const cmd::CopyBufferToTexture& r) { list.copyBufferToTexture(m()[r.dst], r.at, m()[r.src], r.srcOffset); }
    void operator()(const cmd::CopyTextureToBuffer& r) { list.copyTextureToBuffer(m()[r.dst], r.dstOffset, m()[r.src], r.at); }
    void operator()(const cmd::CopyBufferToTextureRegion& r) { list.copyBufferToTexture(m()[r.dst], r.region, m()[r.src], r.layout); }
    void operator()(const cmd::CopyTextureToBufferRegion& r) { list.copyTextureToBuffer(m()[r.dst], r.layout, m()[r.src], r.region); }
    void operator()(const cmd::CopyTextureRegion& r) { list.copyTexture(m()[r.dst], r.dstAt, m()[r.src], r.srcRegion); }
    void operator()(const cmd::BeginTimer& r) { list.beginTimer(m()[r.timer]); }
    void operator()(const cmd::EndTimer& r) { list.endTimer(m()[r.timer]); }
    void operator()(const cmd::BeginQuery& r) { list.beginQuery(m()[r.set], r.index); }
    void operator()(const cmd::EndQuery& r) { list.endQuery(m()[r.set], r.index); }
    void operator()(const cmd::WriteTimestamp& r) { list.writeTimestamp(m()[r.set], r.index); }
    void operator()(const cmd::ResolveQueries& r) { list.resolveQueries(m()[r.set], r.first, r.count, m()[r.dst], r.dstOffset); }
    void operator()(const cmd::PushDebugGroup& r) { list.pushDebugGroup(cmd::view(r, r.name)); }
    void operator()(const cmd::PopDebugGroup&) { list.popDebugGroup(); }
    void operator()(const cmd::InsertDebugLabel& r) { list.insertDebugLabel(cmd::view(r, r.name)); }
    void operator()(const cmd::ClearBuffer& r) { list.clearBuffer(m()[r.buffer], r.offset, r.size, r.value); }
    void operator()(const cmd::DiscardTexture& r) { list.discardTexture(m()[r.texture]); }
    void operator()(const cmd::SetAutomaticBarriers& r) { list.setAutomaticBarriers(r.enabled); }
    void operator()(const cmd::TextureBarriers& r) {
        std::vector<TextureBarrier> b(cmd::view(r, r.barriers).begin(), cmd::view(r, r.barriers).end());
        for (TextureBarrier& x : b) x.texture = m()[x.texture];
        list.barrier(b.data(), uint32_t(b.size()));
    }
    void operator()(const cmd::BufferBarriers& r) {
        std::vector<BufferBarrier> b(cmd::view(r, r.barriers).begin(), cmd::view(r, r.barriers).end());
        for (BufferBarrier& x : b) x.buffer = m()[x.buffer];
        list.barrier(b.data(), uint32_t(b.size()));
    }
    void operator()(const cmd::ExecuteSecondary& r) {
        auto secondary = device.createCommandList();
        secondary->beginSecondary(pass);
        applyStream(stream.child(r.child), device, *secondary, map);
        secondary->endSecondary();
        list.executeSecondary(*secondary);  // takes the recording: the list may go
    }
};

}  // namespace

void applyStream(const cmd::CommandStream& stream, Device& device, CommandList& list, const HandleMap& map,
                 ApplyObserver* observer) {
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
