// Layer 3 (Representation): maps typed handles to a backend's objects.
// Ids carry a generation so a stale handle to a reused slot is caught, not misused.
//
// Storage: Contiguous (one array: a lookup is one indirection, for the per-draw lookups of
// buffers and textures; objects move when the pool grows) or Pinned (fixed-size chunks:
// objects never move, for pipelines, which a command list keeps a pointer to while the
// renderer may create more mid-recording).
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

enum class PoolStorage { Contiguous, Pinned };

template <class H, class T, PoolStorage kStorage = PoolStorage::Contiguous>
class HandlePool {
public:
    H add(T&& object) {
        uint32_t index;
        if (!free_.empty()) {
            index = free_.back();
            free_.pop_back();
        } else {
            index = count_++;
            if constexpr (kStorage == PoolStorage::Pinned) {
                if ((index & kChunkMask) == 0) chunks_.push_back(std::make_unique<Chunk>());
            } else {
                slots_.emplace_back();
            }
        }
        Slot& s = slot(index);
        s.object = std::move(object);
        s.liveTag = s.generation & 0xfffu;
        return H{(s.liveTag << 20) | (index + 1)};
    }
    T* find(H h) {
        // Index 0 wraps to the largest value and fails the bound check too.
        const uint32_t index = (h.id & 0xfffffu) - 1u;
        if (index >= count_) return nullptr;
        Slot& s = slot(index);
        if (s.liveTag != (h.id >> 20)) return nullptr;  // dead slots never match: one compare
        return &s.object;
    }
    const T* find(H h) const { return const_cast<HandlePool*>(this)->find(h); }
    T& get(H h, const char* what) {  // inline fast path: looked up on every bind
        if (T* p = find(h)) [[likely]]
            return *p;
        invalidHandle(h.id, what);
    }
    const T& get(H h, const char* what) const { return const_cast<HandlePool*>(this)->get(h, what); }
    // Removes and returns the object so the caller can release its native resources.
    bool remove(H h, T& out) {
        T* p = find(h);
        if (!p) return false;
        out = std::move(*p);
        *p = T{};
        Slot& s = slot((h.id & 0xfffffu) - 1);
        s.liveTag = kDead;
        s.generation++;
        free_.push_back((h.id & 0xfffffu) - 1);
        return true;
    }
    uint32_t size() const { return count_ - uint32_t(free_.size()); }  // live objects
    template <class F>
    void forEach(F&& f) {
        for (uint32_t i = 0; i < count_; ++i)
            if (Slot& s = slot(i); s.liveTag != kDead) f(s.object);
    }

private:
    [[noreturn, gnu::noinline, gnu::cold]] static void invalidHandle(uint32_t id, const char* what) {
        throw Error(std::string("invalid or destroyed ") + what + " handle " + std::to_string(id));
    }
    static constexpr uint32_t kDead = ~0u;  // id >> 20 is at most 0xfff
    struct SlotFields {
        T object{};
        uint32_t generation = 1;
        uint32_t liveTag = kDead;  // generation & 0xfff while alive (the id's top bits)
    };
    // Small slots get a power-of-two stride, so the per-bind lookup indexes with a shift
    // rather than a multiply (a few bytes per object; large objects keep their natural size).
    static constexpr size_t kSlotAlign =
        sizeof(SlotFields) <= 256 ? std::bit_ceil(sizeof(SlotFields)) : alignof(SlotFields);
    struct alignas(kSlotAlign) Slot : SlotFields {};
    // Pinned: about 16 KiB per chunk, a power of two slots: index >> shift picks the chunk.
    static constexpr uint32_t kChunkSlots =
        uint32_t(std::bit_floor(std::max<size_t>(1, size_t(16384) / sizeof(Slot))));
    static constexpr uint32_t kChunkShift = uint32_t(std::countr_zero(kChunkSlots));
    static constexpr uint32_t kChunkMask = kChunkSlots - 1;
    using Chunk = std::array<Slot, kChunkSlots>;
    Slot& slot(uint32_t index) {
        if constexpr (kStorage == PoolStorage::Pinned)
            return (*chunks_[index >> kChunkShift])[index & kChunkMask];
        else
            return slots_[index];
    }

    std::vector<Slot> slots_;                    // Contiguous
    std::vector<std::unique_ptr<Chunk>> chunks_;  // Pinned
    std::vector<uint32_t> free_;
    uint32_t count_ = 0;  // slots in use or freed: the next new index
};

}  // namespace fe::gdi
