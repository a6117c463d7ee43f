// Layer 5 (Communication): frames in flight. Each frame slot owns a command list, a fence and
// a region of a per-frame upload ring; beginFrame() waits only for the frame that last used
// the same slot, so the CPU records frame N+1 while the GPU still executes frame N.
#pragma once
#include <memory>
#include <vector>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"

namespace fe::render {

// Sub-allocates per-frame constants from one CPU-visible buffer. Each frame slot has its
// own region, reused only after that slot's fence signalled.
struct UploadAllocation {
    gdi::BufferHandle buffer;
    uint64_t offset = 0;
    uint64_t size = 0;
};

class CommandQueue {
public:
    CommandQueue(gdi::Device& device, uint32_t framesInFlight = 2,
                 uint64_t uploadBytesPerFrame = 4u << 20);
    ~CommandQueue();
    CommandQueue(const CommandQueue&) = delete;
    CommandQueue& operator=(const CommandQueue&) = delete;

    gdi::CommandList& beginFrame();
    gdi::FenceValue endFrame();  // submits the frame's command list
    // Submits what the frame has recorded so far; recording goes on in the same list (a
    // profiling run's flush-and-wait between passes).
    gdi::FenceValue flush();
    void waitIdle();

    // Copies `size` bytes into this frame's upload region; aligned for uniform/storage binding.
    UploadAllocation upload(gdi::ByteSpan data);
    template <class T>
    UploadAllocation upload(const T& value) {
        return upload(gdi::bytesOf(value));
    }

    uint64_t frameNumber() const { return frameNumber_; }
    uint32_t framesInFlight() const { return uint32_t(slots_.size()); }
    gdi::Device& device() { return device_; }

private:
    struct Slot {
        std::unique_ptr<gdi::CommandList> commands;
        gdi::FenceValue fence = 0;
    };
    gdi::DeviceObjects objects_;
    gdi::Device& device_;
    std::vector<Slot> slots_;
    gdi::BufferHandle uploadBuffer_;
    uint64_t regionSize_;
    uint64_t regionUsed_ = 0;
    uint64_t alignment_ = 256;
    uint64_t frameNumber_ = 0;
    bool inFrame_ = false;
};

}  // namespace fe::render
