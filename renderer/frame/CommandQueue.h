// Layer 5 (Communication): frames in flight. Each frame slot owns a command list, a fence and
// a region of a per-frame upload ring; beginFrame() waits only for the frame that last used
// the same slot, so the CPU records frame N+1 while the GPU still executes frame N.
// A frame may be cut into several submissions on the graphics queue and lists on the compute
// queue (async compute: RenderGraph::execute(CommandQueue&)); the frame's fence is its last
// graphics submission's, which the others precede or are waited for by.
#pragma once
#include <memory>
#include <vector>

#include "fe/gdi/Device.h"
#include "fe/gdi/DeviceObjects.h"

namespace fe::render {

// Sub-allocates per-frame constants from one CPU-visible buffer. Each frame slot has its
// own region, reused only after that slot's fence signalled. A frame that uploads more than a
// region holds moves to a buffer of regions twice as large (or as large as the upload), and the
// outgrown buffer goes once the frame is submitted: the regions start small (a new buffer is
// zeroed and its pages touched, 8 MiB of them cost a renderer 30 ms on the CPU rasterizers) and
// fit the scene after its first frame.
struct UploadAllocation {
    gdi::BufferHandle buffer;
    uint64_t offset = 0;
    uint64_t size = 0;
};

class CommandQueue {
public:
    // uploadBytesPerFrame: each region's first size.
    CommandQueue(gdi::Device& device, uint32_t framesInFlight = 2,
                 uint64_t uploadBytesPerFrame = 256u << 10);
    ~CommandQueue();
    CommandQueue(const CommandQueue&) = delete;
    CommandQueue& operator=(const CommandQueue&) = delete;

    gdi::CommandList& beginFrame();
    gdi::FenceValue endFrame();  // submits the frame's command list
    // Submits what the frame has recorded so far; recording goes on in the same list (a
    // profiling run's flush-and-wait between passes).
    gdi::FenceValue flush();
    void waitIdle();

    // Async compute within a frame. graphics(): the graphics list being recorded (beginFrame's
    // at first). submitGraphics(): submits it, waiting for what graphicsWaits() named, and
    // starts the next one. compute(): a compute-queue list of this frame, submitted by
    // submitCompute(list, waitFor). graphicsWaits(fence): the next graphics submission (or
    // endFrame's) waits for it.
    gdi::CommandList& graphics();
    gdi::FenceValue submitGraphics();
    gdi::CommandList& compute();
    gdi::FenceValue submitCompute(gdi::CommandList& list, gdi::FenceValue waitFor);
    void graphicsWaits(gdi::FenceValue fence);
    // What the frame being recorded (after endFrame: the last frame) submitted, in order.
    struct Submission {
        gdi::QueueKind queue = gdi::QueueKind::Graphics;
        gdi::FenceValue fence = 0, waitFor = 0;
    };
    const std::vector<Submission>& submissions() const { return submissions_; }

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
        // The frame's further lists, reused frame after frame (async compute's cuts).
        std::vector<std::unique_ptr<gdi::CommandList>> moreGraphics, computeLists;
    };
    Slot& slot() { return slots_[frameNumber_ % slots_.size()]; }
    gdi::FenceValue submitCurrent();
    gdi::DeviceObjects objects_;
    gdi::Device& device_;
    std::vector<Slot> slots_;
    void createUploadBuffer();
    void outgrowRegion(uint64_t upload);
    gdi::BufferHandle uploadBuffer_;
    std::vector<gdi::BufferHandle> outgrown_;  // destroyed once this frame is submitted
    uint64_t regionSize_;
    uint64_t regionUsed_ = 0;
    uint64_t alignment_ = 256;
    uint64_t frameNumber_ = 0;
    bool inFrame_ = false;
    gdi::CommandList* current_ = nullptr;  // the graphics list being recorded
    size_t graphicsUsed_ = 0, computeUsed_ = 0;
    gdi::FenceValue graphicsWait_ = 0;
    std::vector<Submission> submissions_;
};

}  // namespace fe::render
