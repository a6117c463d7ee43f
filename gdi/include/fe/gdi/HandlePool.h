// Layer 3 (Representation): maps typed handles to a backend's objects.
// Ids carry a generation so a stale handle to a reused slot is caught, not misused.
//
// Threads: lookups (find, get, at) take no lock and may run on any number of threads while
// one thread at a time adds, retires or removes (the backends' device lock serialises those).
// That is what lets command lists be recorded on several threads while another creates and
// destroys objects. It holds because objects never move: slots live in fixed-size chunks
// reached through a table sized for every possible index, inside the pool, so growing it
// publishes a new chunk and never reallocates what a reader is looking at; a slot's tag is
// published with release after its object is written, and read with acquire.
//
// Two-step removal, for work that still runs after the caller's destroy(): retire() makes the
// handle invalid for find()/get() at once but keeps the object in its slot; at() still reaches
// it (for replaying already-validated work); release() frees the slot later.
//
// A recording thread may have found an object just before another thread destroys it (a misuse
// the list's submit refuses, which must not crash first). So release() copies the object out
// and leaves the slot as it was, and a freed slot waits in a first-in first-out quarantine of
// kQuarantine others before add() writes a new object there: a reader that found the handle
// reads an intact (stale) object, not one being overwritten.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

// Each device's pools start their generations at a salt of its own, so that a handle given to
// another device than the one that made it (its index may well exist there too) fails find()
// instead of naming that device's object. Ids are 32 bits with 12 of generation, so this
// catches the mistake with near certainty, not always: a salt stride of 0x9e5 (odd, so 4096
// devices pass before a salt repeats) puts devices made one after the other 1,563 generations
// apart. The first device of a process keeps salt 0: ids of a one-device program (captures,
// messages) are what they always were.
inline uint32_t nextHandleSalt() {
    static std::atomic<uint32_t> devices{0};
    return (devices.fetch_add(1, std::memory_order_relaxed) * 0x9e5u) & 0xfffu;
}

template <class H, class T>
class HandlePool {
public:
    HandlePool() = default;
    explicit HandlePool(uint32_t salt) : salt_(salt & 0xfffu) {}
    ~HandlePool() {
        for (uint32_t c = 0; c < kMaxChunks; ++c) delete chunks_[c].load(std::memory_order_relaxed);
    }
    HandlePool(const HandlePool&) = delete;
    HandlePool& operator=(const HandlePool&) = delete;

    H add(T&& object) {
        uint32_t index;
        const bool full = count_.load(std::memory_order_relaxed) >= kMaxIndex;  // then reuse sooner
        if (free_.size() > kQuarantine || (full && !free_.empty())) {
            index = free_.front();
            free_.pop_front();
        } else {
            index = count_.load(std::memory_order_relaxed);
            if (index >= kMaxIndex)
                throw Error("too many live objects of one kind (at most " +
                            std::to_string(kMaxIndex) + ")");
            if ((index & kChunkMask) == 0)
                chunks_[index >> kChunkShift].store(new Chunk, std::memory_order_release);
            count_.store(index + 1, std::memory_order_release);
            slot(index).generation += salt_;  // a new slot: its first generation is the salt's
        }
        Slot& s = slot(index);
        s.object = std::move(object);
        const uint32_t tag = s.generation & 0xfffu;
        s.liveTag.store(tag, std::memory_order_release);
        return H{(tag << 20) | (index + 1)};
    }
    T* find(H h) {
        // Index 0 wraps to the largest value and fails the bound check too.
        const uint32_t index = (h.id & 0xfffffu) - 1u;
        if (index >= count_.load(std::memory_order_acquire)) return nullptr;
        Slot& s = slot(index);
        if (s.liveTag.load(std::memory_order_acquire) != (h.id >> 20))
            return nullptr;  // dead slots never match
        return &s.object;
    }
    const T* find(H h) const { return const_cast<HandlePool*>(this)->find(h); }
    T& get(H h, const char* what) {  // inline fast path: looked up on every bind
        if (T* p = find(h)) [[likely]]
            return *p;
        invalidHandle(h.id, what);
    }
    const T& get(H h, const char* what) const {
        return const_cast<HandlePool*>(this)->get(h, what);
    }
    // The object of a live or retired (not yet released) handle, without the liveness check:
    // for replaying work whose handles were checked when it was recorded.
    T& at(H h) { return slot((h.id & 0xfffffu) - 1).object; }

    // Removes and returns the object so the caller can release its native resources.
    bool remove(H h, T& out) {
        if (!retire(h)) return false;
        release(h, out);
        return true;
    }
    // The handle stops being valid; the object stays where at() finds it until release().
    bool retire(H h) {
        if (!find(h)) return false;
        slot((h.id & 0xfffffu) - 1).liveTag.store(kDead, std::memory_order_release);
        return true;
    }
    // Frees a retired handle's slot, copying its object out (the slot keeps it until reused).
    void release(H h, T& out) {
        const uint32_t index = (h.id & 0xfffffu) - 1;
        Slot& s = slot(index);
        out = s.object;
        s.generation++;
        free_.push_back(index);
    }
    uint32_t size() const {
        return count_.load(std::memory_order_acquire) - uint32_t(free_.size());
    }  // live + retired
    template <class F>
    void forEach(F&& f) {
        const uint32_t n = count_.load(std::memory_order_acquire);
        for (uint32_t i = 0; i < n; ++i)
            if (Slot& s = slot(i); s.liveTag.load(std::memory_order_acquire) != kDead) f(s.object);
    }

private:
    [[noreturn, gnu::noinline, gnu::cold]] static void invalidHandle(uint32_t id,
                                                                     const char* what) {
        throw Error(std::string("invalid or destroyed ") + what + " handle " + std::to_string(id) +
                    " (or one made by another device)");
    }
    static constexpr uint32_t kDead = ~0u;                 // id >> 20 is at most 0xfff
    static constexpr uint32_t kMaxIndex = (1u << 20) - 1;  // ids keep 20 bits of index
    struct SlotFields {
        T object{};
        uint32_t generation = 1;
        std::atomic<uint32_t> liveTag{kDead};  // generation & 0xfff while alive (the id's top bits)
    };
    // Small slots get a power-of-two stride, so the per-bind lookup indexes with a shift
    // rather than a multiply (a few bytes per object; large objects keep their natural size).
    static constexpr size_t kSlotAlign =
        sizeof(SlotFields) <= 256 ? std::bit_ceil(sizeof(SlotFields)) : alignof(SlotFields);
    struct alignas(kSlotAlign) Slot : SlotFields {};
    // About 16 KiB per chunk, a power of two slots: index >> shift picks the chunk. At least 16
    // slots: the table of chunks is inline, and with a slot of 4.6 KiB (a Vulkan pipeline) two a
    // chunk made it 4 MiB, zeroed with every device.
    static constexpr uint32_t kChunkSlots =
        uint32_t(std::bit_floor(std::max<size_t>(16, size_t(16384) / sizeof(Slot))));
    static constexpr uint32_t kChunkShift = uint32_t(std::countr_zero(kChunkSlots));
    static constexpr uint32_t kChunkMask = kChunkSlots - 1;
    static constexpr uint32_t kMaxChunks = (kMaxIndex >> kChunkShift) + 1;
    using Chunk = std::array<Slot, kChunkSlots>;
    Slot& slot(uint32_t index) {
        return (*chunks_[index >> kChunkShift].load(std::memory_order_acquire))[index & kChunkMask];
    }

    // Inline, not behind a pointer: a lookup is one load for the chunk, one for the slot.
    std::array<std::atomic<Chunk*>, kMaxChunks> chunks_{};  // null until used
    static constexpr size_t kQuarantine = 64;
    std::deque<uint32_t> free_;       // released slots, oldest first
    std::atomic<uint32_t> count_{0};  // slots in use or freed: the next new index
    uint32_t salt_ = 0;               // see nextHandleSalt()
};

}  // namespace fe::gdi
