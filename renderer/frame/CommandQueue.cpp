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
    uploadBuffer_ = objects_.add(
        device.createBuffer({.size = regionSize_ * framesInFlight,
                             .usage = gdi::BufferUsage::Uniform | gdi::BufferUsage::Storage |
                                      gdi::BufferUsage::Vertex | gdi::BufferUsage::Index,
                             .access = gdi::MemoryAccess::Upload,
                             .debugName = "per-frame uploads"}));
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
    return *s.commands;
}

gdi::FenceValue CommandQueue::endFrame() {
    if (!inFrame_) throw gdi::Error("CommandQueue::endFrame without beginFrame");
    Slot& s = slots_[frameNumber_ % slots_.size()];
    s.fence = device_.submit(*s.commands);
    gdi::markFrameEnd(device_);  // a capture's frames are the queue's frames (headless too)
    inFrame_ = false;
    ++frameNumber_;
    return s.fence;
}

gdi::FenceValue CommandQueue::flush() {
    if (!inFrame_) throw gdi::Error("CommandQueue::flush outside a frame");
    return device_.submit(*slots_[frameNumber_ % slots_.size()].commands);
}

void CommandQueue::waitIdle() {
    for (Slot& s : slots_)
        if (s.fence) device_.wait(s.fence);
}

UploadAllocation CommandQueue::upload(gdi::ByteSpan data) {
    const uint64_t size = data.size();
    if (!inFrame_) throw gdi::Error("CommandQueue::upload outside a frame");
    uint64_t offset = (regionUsed_ + alignment_ - 1) / alignment_ * alignment_;
    if (offset + size > regionSize_)
        throw gdi::Error("CommandQueue: per-frame upload region of " + std::to_string(regionSize_) +
                         " bytes exhausted (asked " + std::to_string(size) + ")");
    regionUsed_ = offset + size;
    uint64_t base = (frameNumber_ % slots_.size()) * regionSize_;
    device_.writeBuffer(uploadBuffer_, base + offset, data);
    return {uploadBuffer_, base + offset, size};
}

}  // namespace fe::render
