// One thread per command list at a time, checked with an atomic flag per list (ExclusiveUse.h).
#include "fe/gdi/ExclusiveUse.h"

#include <string>

#include "fe/gdi/Validation.h"

namespace fe::gdi {

namespace {

std::shared_mutex& layerMutex() {
    static std::shared_mutex m;
    return m;
}
thread_local uint32_t layerCallDepth = 0;  // NativeLayerLock::Call nesting on this thread

}  // namespace

NativeLayerLock::Call::Call(bool active) : active_(active) {
    if (active_ && layerCallDepth++ == 0) layerMutex().lock_shared();
}

NativeLayerLock::Call::~Call() {
    if (active_ && --layerCallDepth == 0) layerMutex().unlock_shared();
}

// Holding it alone counts as being inside a call, so that the device's own calls during its
// making or destruction pass on this thread.
NativeLayerLock::Change::Change(bool active) : active_(active && layerCallDepth == 0) {
    if (!active_) return;
    layerMutex().lock();
    ++layerCallDepth;
}

NativeLayerLock::Change::~Change() {
    if (!active_) return;
    --layerCallDepth;
    layerMutex().unlock();
}

namespace {

[[noreturn, gnu::cold, gnu::noinline]] void inUse(const char* what) {
    throw Error(std::string(what) +
                ": the command list is in use by another thread at the same time (a list is used by one thread at "
                "a time: record each thread's work in its own list, or hand the list over when a call has returned)");
}

// Holds a list's flag for one call. The exchange is exact: of two threads arriving at once one
// gets the list and the other the Error, whatever the interleaving (acquire and release also
// order a list handed from one thread to the next).
class Claim {
public:
    Claim(std::atomic<bool>& busy, const char* what) : busy_(busy) {
        if (busy_.exchange(true, std::memory_order_acquire)) [[unlikely]]
            inUse(what);
    }
    ~Claim() { busy_.store(false, std::memory_order_release); }
    Claim(const Claim&) = delete;
    Claim& operator=(const Claim&) = delete;

private:
    std::atomic<bool>& busy_;
};

// Every CommandList call, claimed, then passed to the backend's list (whose checks and errors
// are the backend's, unchanged). __func__ names the call in the Error.
#define FE_CLAIMED(call)                                \
    {                                                   \
        const NativeLayerLock::Call layer(layerLock_); \
        const Claim claim(busy_, __func__);             \
        return inner_->call;                            \
    }

class ExclusiveCommandList final : public CommandList {
public:
    ExclusiveCommandList(std::unique_ptr<CommandList> inner, bool layerLock)
        : inner_(std::move(inner)), layerLock_(layerLock) {}
    ~ExclusiveCommandList() override {
        const NativeLayerLock::Call layer(layerLock_);  // the backend's list frees native objects
        inner_.reset();
    }
    CommandList& inner() { return *inner_; }
    std::atomic<bool>& busy() { return busy_; }

    void beginRenderPass(const RenderPassDesc& d) override FE_CLAIMED(beginRenderPass(d))
    void endRenderPass() override FE_CLAIMED(endRenderPass())
    void setPipeline(PipelineHandle p) override FE_CLAIMED(setPipeline(p))
    void setViewport(const Viewport& v) override FE_CLAIMED(setViewport(v))
    void setScissor(const Rect& r) override FE_CLAIMED(setScissor(r))
    void setBlendConstant(const std::array<float, 4>& c) override FE_CLAIMED(setBlendConstant(c))
    void setStencilReference(uint8_t r) override FE_CLAIMED(setStencilReference(r))
    void setDepthBias(float c, float s, float k) override FE_CLAIMED(setDepthBias(c, s, k))
    void setConstants(uint32_t o, ByteSpan d) override FE_CLAIMED(setConstants(o, d))
    void setVertexBuffer(uint32_t i, BufferHandle b, uint64_t o) override FE_CLAIMED(setVertexBuffer(i, b, o))
    void setIndexBuffer(BufferHandle b, IndexType t, uint64_t o) override FE_CLAIMED(setIndexBuffer(b, t, o))
    void setUniformBuffer(uint32_t s, BufferHandle b, uint64_t o, uint64_t n) override
        FE_CLAIMED(setUniformBuffer(s, b, o, n))
    void setStorageBuffer(uint32_t s, BufferHandle b, uint64_t o, uint64_t n) override
        FE_CLAIMED(setStorageBuffer(s, b, o, n))
    void setTexture(uint32_t s, TextureHandle t, SamplerHandle p) override FE_CLAIMED(setTexture(s, t, p))
    void setStorageTexture(uint32_t s, TextureHandle t, uint32_t m) override FE_CLAIMED(setStorageTexture(s, t, m))
    void draw(uint32_t v, uint32_t i, uint32_t fv, uint32_t fi) override FE_CLAIMED(draw(v, i, fv, fi))
    void drawIndexed(uint32_t n, uint32_t i, uint32_t fi, int32_t bv, uint32_t fin) override
        FE_CLAIMED(drawIndexed(n, i, fi, bv, fin))
    void dispatch(uint32_t x, uint32_t y, uint32_t z) override FE_CLAIMED(dispatch(x, y, z))
    void drawIndirect(BufferHandle a, uint64_t o, uint32_t n, uint32_t s) override FE_CLAIMED(drawIndirect(a, o, n, s))
    void drawIndexedIndirect(BufferHandle a, uint64_t o, uint32_t n, uint32_t s) override
        FE_CLAIMED(drawIndexedIndirect(a, o, n, s))
    void drawIndirectCount(BufferHandle a, uint64_t o, BufferHandle c, uint64_t co, uint32_t m, uint32_t s) override
        FE_CLAIMED(drawIndirectCount(a, o, c, co, m, s))
    void drawIndexedIndirectCount(BufferHandle a, uint64_t o, BufferHandle c, uint64_t co, uint32_t m,
                                  uint32_t s) override FE_CLAIMED(drawIndexedIndirectCount(a, o, c, co, m, s))
    void dispatchIndirect(BufferHandle a, uint64_t o) override FE_CLAIMED(dispatchIndirect(a, o))
    void generateMips(TextureHandle t) override FE_CLAIMED(generateMips(t))
    void copyBuffer(BufferHandle d, uint64_t doff, BufferHandle s, uint64_t soff, uint64_t n) override
        FE_CLAIMED(copyBuffer(d, doff, s, soff, n))
    void clearBuffer(BufferHandle b, uint64_t o, uint64_t n, uint32_t v) override FE_CLAIMED(clearBuffer(b, o, n, v))
    void copyTexture(TextureHandle d, TextureHandle s, uint32_t m) override FE_CLAIMED(copyTexture(d, s, m))
    void copyBufferToTexture(TextureHandle d, Subresource at, BufferHandle s, uint64_t o) override
        FE_CLAIMED(copyBufferToTexture(d, at, s, o))
    void copyTextureToBuffer(BufferHandle d, uint64_t o, TextureHandle s, Subresource at) override
        FE_CLAIMED(copyTextureToBuffer(d, o, s, at))
    void copyBufferToTexture(TextureHandle d, const TextureRegion& r, BufferHandle s, const TexelLayout& l) override
        FE_CLAIMED(copyBufferToTexture(d, r, s, l))
    void copyTextureToBuffer(BufferHandle d, const TexelLayout& l, TextureHandle s, const TextureRegion& r) override
        FE_CLAIMED(copyTextureToBuffer(d, l, s, r))
    void copyTexture(TextureHandle d, const TextureRegion& at, TextureHandle s, const TextureRegion& r) override
        FE_CLAIMED(copyTexture(d, at, s, r))
    void beginTimer(TimerHandle t) override FE_CLAIMED(beginTimer(t))
    void endTimer(TimerHandle t) override FE_CLAIMED(endTimer(t))
    void beginQuery(QuerySetHandle q, uint32_t i) override FE_CLAIMED(beginQuery(q, i))
    void endQuery(QuerySetHandle q, uint32_t i) override FE_CLAIMED(endQuery(q, i))
    void writeTimestamp(QuerySetHandle q, uint32_t i) override FE_CLAIMED(writeTimestamp(q, i))
    void resolveQueries(QuerySetHandle q, uint32_t f, uint32_t n, BufferHandle d, uint64_t o) override
        FE_CLAIMED(resolveQueries(q, f, n, d, o))
    void pushDebugGroup(const char* name) override FE_CLAIMED(pushDebugGroup(name))
    void popDebugGroup() override FE_CLAIMED(popDebugGroup())
    void insertDebugLabel(const char* name) override FE_CLAIMED(insertDebugLabel(name))
    void discardTexture(TextureHandle t) override FE_CLAIMED(discardTexture(t))
    void setAutomaticBarriers(bool on) override FE_CLAIMED(setAutomaticBarriers(on))
    void barrier(const TextureBarrier* b, uint32_t n) override FE_CLAIMED(barrier(b, n))
    void barrier(const BufferBarrier* b, uint32_t n) override FE_CLAIMED(barrier(b, n))
    void beginSecondary(const RenderPassDesc& pass) override FE_CLAIMED(beginSecondary(pass))
    void endSecondary() override FE_CLAIMED(endSecondary())
    // The executed lists are taken too: one still being recorded by a worker is refused.
    void executeSecondary(std::span<CommandList* const> lists) override {
        const NativeLayerLock::Call layer(layerLock_);
        const Claim claim(busy_, __func__);
        const ClaimedLists parts(lists, __func__, this);
        inner_->executeSecondary(parts.lists());
    }
    uint64_t nativeCommandBuffer() override FE_CLAIMED(nativeCommandBuffer())

private:
    std::unique_ptr<CommandList> inner_;
    bool layerLock_;
    std::atomic<bool> busy_{false};
};

#undef FE_CLAIMED

}  // namespace

std::unique_ptr<CommandList> exclusiveUse(std::unique_ptr<CommandList> list, bool layerLock) {
    return std::make_unique<ExclusiveCommandList>(std::move(list), layerLock);
}

ClaimedLists::ClaimedLists(std::span<CommandList* const> lists, const char* what, const CommandList* self) {
    validate::submittedLists(lists);
    inner_.reserve(lists.size());
    try {
        for (CommandList* l : lists) {
            auto* checked = dynamic_cast<ExclusiveCommandList*>(l);
            if (!checked) {
                inner_.push_back(l);
                continue;
            }
            if (l != self) {
                if (checked->busy().exchange(true, std::memory_order_acquire)) inUse(what);
                held_.push_back(&checked->busy());
            }
            inner_.push_back(&checked->inner());
        }
    } catch (...) {
        release();
        throw;
    }
}

ClaimedLists::~ClaimedLists() { release(); }

void ClaimedLists::release() {
    for (std::atomic<bool>* busy : held_) busy->store(false, std::memory_order_release);
    held_.clear();
}

}  // namespace fe::gdi
