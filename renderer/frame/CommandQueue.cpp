#include "CommandQueue.h"

#include <algorithm>

#include "fe/gdi/Capture.h"
#include <string>

namespace fe::render {

CommandQueue::CommandQueue(gdi::Device& device, uint32_t framesInFlight,
                           uint64_t uploadBytesPerFrame)
    : objects_(device), device_(device), regionSize_(uploadBytesPerFrame) {
    if (framesInFlight == 0 || framesInFlight > 8)
        throw gdi::Error("CommandQueue: framesInFlight must be 1..8");
    const auto& l = device.info().limits;
    alignment_ =
        std::max<uint64_t>({64, l.uniformBufferOffsetAlignment, l.storageBufferOffsetAlignment});
    slots_.resize(framesInFlight);
    for (Slot& s : slots_) s.commands = device.createCommandList();
    if (regionSize_ == 0) throw gdi::Error("CommandQueue: uploadBytesPerFrame must not be 0");
    createUploadBuffer();
}

void CommandQueue::createUploadBuffer() {
    uploadBuffer_ = objects_.add(
        device_.createBuffer({.size = regionSize_ * slots_.size(),
                              .usage = gdi::BufferUsage::Uniform | gdi::BufferUsage::Storage |
                                       gdi::BufferUsage::Vertex | gdi::BufferUsage::Index,
                              .access = gdi::MemoryAccess::Upload,
                              .debugName = "per-frame uploads"}));
}

// This frame's uploads so far stay in the old buffer, which its lists use until submitted.
void CommandQueue::outgrowRegion(uint64_t upload) {
    outgrown_.push_back(uploadBuffer_);
    regionSize_ = std::max(regionSize_ * 2, (upload + alignment_ - 1) / alignment_ * alignment_);
    createUploadBuffer();
    regionUsed_ = 0;
}

CommandQueue::~CommandQueue() {
    device_.waitIdleOrLost();  // a destructor must not throw, and a lost device runs nothing more
}

gdi::CommandList& CommandQueue::beginFrame() {
    if (inFrame_) throw gdi::Error("CommandQueue::beginFrame: previous frame not ended");
    Slot& s = slots_[frameNumber_ % slots_.size()];
    if (s.fence) device_.wait(s.fence);  // this slot's previous frame is done with its region
    regionUsed_ = 0;
    inFrame_ = true;
    current_ = s.commands.get();
    graphicsUsed_ = computeUsed_ = 0;
    graphicsWait_ = 0;
    submissions_.clear();
    return *s.commands;
}

gdi::FenceValue CommandQueue::submitCurrent() {
    const gdi::FenceValue fence = device_.submit(*current_, {.waitFor = graphicsWait_});
    submissions_.push_back({gdi::QueueKind::Graphics, fence, graphicsWait_});
    graphicsWait_ = 0;
    return fence;
}

gdi::CommandList& CommandQueue::graphics() {
    if (!inFrame_) throw gdi::Error("CommandQueue::graphics outside a frame");
    return *current_;
}

gdi::FenceValue CommandQueue::submitGraphics() {
    if (!inFrame_) throw gdi::Error("CommandQueue::submitGraphics outside a frame");
    const gdi::FenceValue fence = submitCurrent();
    Slot& s = slot();
    if (graphicsUsed_ == s.moreGraphics.size())
        s.moreGraphics.push_back(device_.createCommandList());
    current_ = s.moreGraphics[graphicsUsed_++].get();
    return fence;
}

gdi::CommandList& CommandQueue::compute() {
    if (!inFrame_) throw gdi::Error("CommandQueue::compute outside a frame");
    Slot& s = slot();
    if (computeUsed_ == s.computeLists.size())
        s.computeLists.push_back(device_.createCommandList({.queue = gdi::QueueKind::Compute}));
    return *s.computeLists[computeUsed_++];
}

gdi::FenceValue CommandQueue::submitCompute(gdi::CommandList& list, gdi::FenceValue waitFor) {
    if (!inFrame_) throw gdi::Error("CommandQueue::submitCompute outside a frame");
    const gdi::FenceValue fence = device_.submit(list, {.waitFor = waitFor});
    submissions_.push_back({list.queue(), fence, waitFor});
    return fence;
}

void CommandQueue::graphicsWaits(gdi::FenceValue fence) { graphicsWait_ = fence; }

gdi::FenceValue CommandQueue::endFrame() {
    if (!inFrame_) throw gdi::Error("CommandQueue::endFrame without beginFrame");
    Slot& s = slots_[frameNumber_ % slots_.size()];
    s.fence = submitCurrent();
    for (gdi::BufferHandle b : outgrown_) objects_.destroy(b);
    outgrown_.clear();
    gdi::markFrameEnd(device_);  // a capture's frames are the queue's frames (headless too)
    inFrame_ = false;
    ++frameNumber_;
    return s.fence;
}

gdi::FenceValue CommandQueue::flush() {
    if (!inFrame_) throw gdi::Error("CommandQueue::flush outside a frame");
    const gdi::FenceValue fence = device_.submit(*current_);
    submissions_.push_back({gdi::QueueKind::Graphics, fence, 0});
    return fence;
}

void CommandQueue::waitIdle() {
    for (Slot& s : slots_)
        if (s.fence) device_.wait(s.fence);
}

UploadAllocation CommandQueue::upload(gdi::ByteSpan data) {
    const uint64_t size = data.size();
    if (!inFrame_) throw gdi::Error("CommandQueue::upload outside a frame");
    uint64_t offset = (regionUsed_ + alignment_ - 1) / alignment_ * alignment_;
    if (offset + size > regionSize_) {
        outgrowRegion(size);
        offset = 0;
    }
    regionUsed_ = offset + size;
    uint64_t base = (frameNumber_ % slots_.size()) * regionSize_;
    device_.writeBuffer(uploadBuffer_, base + offset, data);
    return {uploadBuffer_, base + offset, size};
}

}  // namespace fe::render
