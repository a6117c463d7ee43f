// Layer 3 (Representation): maps typed handles to a backend's objects.
// Ids carry a generation so a stale handle to a reused slot is caught, not misused.
#pragma once
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
        }
        Slot& s = slots_[index];
        s.object = std::move(object);
        s.alive = true;
        return H{((s.generation & 0xfffu) << 20) | (index + 1)};
    }
    T* find(H h) {
        uint32_t index = (h.id & 0xfffffu);
        if (index == 0 || index > slots_.size()) return nullptr;
        Slot& s = slots_[index - 1];
        if (!s.alive || (s.generation & 0xfffu) != (h.id >> 20)) return nullptr;
        return &s.object;
    }
    const T* find(H h) const { return const_cast<HandlePool*>(this)->find(h); }
    T& get(H h, const char* what) {
        T* p = find(h);
        if (!p) throw Error(std::string("invalid or destroyed ") + what + " handle " + std::to_string(h.id));
        return *p;
    }
    const T& get(H h, const char* what) const { return const_cast<HandlePool*>(this)->get(h, what); }
    // Removes and returns the object so the caller can release its native resources.
    bool remove(H h, T& out) {
        T* p = find(h);
        if (!p) return false;
        out = std::move(*p);
        *p = T{};
        Slot& s = slots_[(h.id & 0xfffffu) - 1];
        s.alive = false;
        s.generation++;
        free_.push_back((h.id & 0xfffffu) - 1);
        return true;
    }
    template <class F>
    void forEach(F&& f) {
        for (auto& s : slots_)
            if (s.alive) f(s.object);
    }

private:
    struct Slot {
        T object{};
        uint32_t generation = 1;
        bool alive = false;
    };
    std::vector<Slot> slots_;
    std::vector<uint32_t> free_;
};

}  // namespace fe::gdi
