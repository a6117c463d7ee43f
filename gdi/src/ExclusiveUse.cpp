// One thread per command list at a time, checked with an atomic flag per list (ExclusiveUse.h).
#include "fe/gdi/ExclusiveUse.h"

#include <string>

#include "fe/gdi/CommandStream.h"
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
    throw Error(
        std::string(what) +
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
#define FE_CLAIMED(call)                               \
    {                                                  \
        const NativeLayerLock::Call layer(layerLock_); \
        const Claim claim(busy_, __func__);            \
        return inner_->call;                           \
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

    // Methods whose bodies are macros, one line each (clang-format reads them as one statement).
    // clang-format off
    FE_CMD_TYPE_NAMES
    // The calls that map field for field to a record, generated from the command set.
#define FE_FIELD(Type, name) (Type, name)
#define FE_COMMAND(Name, Fields)
#define FE_CALL(Name, method, Fields) \
    void method(FE_CMD_PARAMS(Fields)) override FE_CLAIMED(method(FE_CMD_ARGS(Fields)))
#include "fe/gdi/CommandSet.inc"
#undef FE_CALL
#undef FE_COMMAND
#undef FE_FIELD
    // The rest, by hand.
    void beginRenderPass(const RenderPassDesc& d) override FE_CLAIMED(beginRenderPass(d))
    void barrier(const TextureBarrier* b, uint32_t n) override FE_CLAIMED(barrier(b, n))
    void barrier(const BufferBarrier* b, uint32_t n) override FE_CLAIMED(barrier(b, n))
    void beginSecondary(const RenderPassDesc& pass) override FE_CLAIMED(beginSecondary(pass))
    void endSecondary() override FE_CLAIMED(endSecondary())
    void reset() override FE_CLAIMED(reset())
    // The executed lists are taken too: one still being recorded by a worker is refused.
    void executeSecondary(std::span<CommandList* const> lists) override {
        const NativeLayerLock::Call layer(layerLock_);
        const Claim claim(busy_, __func__);
        const ClaimedLists parts(lists, __func__, this);
        inner_->executeSecondary(parts.lists());
    }
    uint64_t nativeCommandBuffer() override FE_CLAIMED(nativeCommandBuffer())
    QueueKind queue() const override { return inner_->queue(); }  // fixed at creation

private:
    std::unique_ptr<CommandList> inner_;
    bool layerLock_;
    std::atomic<bool> busy_{false};
    // clang-format on
};

#undef FE_CLAIMED

}  // namespace

std::unique_ptr<CommandList> exclusiveUse(std::unique_ptr<CommandList> list, bool layerLock) {
    return std::make_unique<ExclusiveCommandList>(std::move(list), layerLock);
}

ClaimedLists::ClaimedLists(std::span<CommandList* const> lists, const char* what,
                           const CommandList* self) {
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
