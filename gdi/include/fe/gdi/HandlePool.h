// Layer 3 (Representation): maps typed handles to a backend's objects.
// Ids carry a generation so a stale handle to a reused slot is caught, not misused.
#pragma once
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

template <class H, class T>
class HandlePool {
public:
    H add(T&& object) {
        uint32_t index;
        if (!free_.empty()) {
            index = free_.back();
            free_.pop_back();
        } else {
            index = uint32_t(slots_.size());
            slots_.push_back({});
            count_ = uint32_t(slots_.size());
        }
        Slot& s = slots_[index];
        s.object = std::move(object);
        s.liveTag = s.generation & 0xfffu;
        return H{(s.liveTag << 20) | (index + 1)};
    }
    T* find(H h) {
        // Index 0 wraps to the largest value and fails the bound check too; count_ avoids
        // dividing by sizeof(Slot) in size() on every lookup.
        const uint32_t index = (h.id & 0xfffffu) - 1u;
        if (index >= count_) return nullptr;
        Slot& s = slots_[index];
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
        Slot& s = slots_[(h.id & 0xfffffu) - 1];
        s.liveTag = kDead;
        s.generation++;
        free_.push_back((h.id & 0xfffffu) - 1);
        return true;
    }
    template <class F>
    void forEach(F&& f) {
        for (auto& s : slots_)
            if (s.liveTag != kDead) f(s.object);
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
    std::vector<Slot> slots_;
    std::vector<uint32_t> free_;
    uint32_t count_ = 0;  // slots_.size()
};

}  // namespace fe::gdi
