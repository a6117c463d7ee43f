// Ownership of device objects for the classes that make them (layers 5-8): a class adds each
// object it creates to its DeviceObjects member and never destroys it by hand. The set destroys
// them, newest first, when it is destroyed, so an exception half-way through a constructor (an
// out-of-memory error, a lost device) leaves nothing behind: the members already constructed
// are destroyed as the exception leaves, which is where hand-written destructors fail.
//
//   class Blur {
//       gdi::DeviceObjects objects_;  // first: the handles below are only views of it
//       gdi::ShaderHandle fs_;
//       gdi::PipelineHandle pipeline_;
//   public:
//       explicit Blur(gdi::Device& d) : objects_(d) {
//           fs_ = objects_.add(d.createShader({...}));
//           pipeline_ = objects_.add(d.createGraphicsPipeline({... fs_ ...}));  // may throw: fs_ is freed
//       }
//   };
//
// Newest first also destroys placed textures before their heap. A class whose objects are in
// flight on the GPU waits for them in its own destructor body, which runs before its members go.
#pragma once
#include <algorithm>
#include <cstdio>
#include <variant>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

class DeviceObjects {
public:
    explicit DeviceObjects(Device& device) : device_(&device) {}
    DeviceObjects(const DeviceObjects&) = delete;
    DeviceObjects& operator=(const DeviceObjects&) = delete;
    // A destroy that fails here (a view of a texture kept alive elsewhere) cannot throw out of a
    // destructor: it is reported on stderr and that object is left to the device, which frees it
    // when the device goes.
    ~DeviceObjects() {
        while (!objects_.empty()) {
            try {
                clear();
            } catch (const Error& e) {
                std::fprintf(stderr, "fe: DeviceObjects: %s (left to the device)\n", e.what());
            }
        }
    }

    // Takes ownership of `h` (a null handle is ignored) and returns it.
    template <class H>
    H add(H h) {
        if (h) objects_.push_back(h);
        return h;
    }
    // Destroys `h` now, if held, and nulls it.
    template <class H>
    void destroy(H& h) {
        if (!h) return;
        auto it = std::find_if(objects_.begin(), objects_.end(), [&](const Object& o) {
            const H* held = std::get_if<H>(&o);
            return held && held->id == h.id;
        });
        if (it != objects_.end()) {
            objects_.erase(it);
            device_->destroy(h);
        }
        h = {};
    }
    // Destroys every object, newest first.
    void clear() {
        while (!objects_.empty()) {
            Object o = objects_.back();
            objects_.pop_back();
            std::visit([&](auto h) { device_->destroy(h); }, o);
        }
    }
    Device& device() const { return *device_; }
    size_t size() const { return objects_.size(); }

private:
    using Object = std::variant<BufferHandle, TextureHandle, SamplerHandle, ShaderHandle,
                                PipelineHandle, TimerHandle, HeapHandle, QuerySetHandle>;
    Device* device_;
    std::vector<Object> objects_;
};

}  // namespace fe::gdi
