// Layer 2 (GDI abstraction): checks every backend runs on descriptions before touching the
// native API, so invalid input gives the same clear message on Vulkan and GL.
#pragma once
#include "fe/gdi/Device.h"

namespace fe::gdi::validate {

// Each throws Error naming the object (debugName when set) and what is wrong.
void bufferDesc(const BufferDesc& d);
void textureDesc(const TextureDesc& d, const DeviceLimits& limits);
void samplerDesc(const SamplerDesc& d);
void shaderDesc(const ShaderDesc& d);
void graphicsPipelineDesc(const GraphicsPipelineDesc& d, const DeviceLimits& limits);
void computePipelineDesc(const ComputePipelineDesc& d);
// Attachment formats/usages/sizes must agree; returns the render area.
struct AttachmentInfo {
    Format format;
    uint32_t width, height;
    TextureUsage usage;
};
Rect renderPass(const RenderPassDesc& d, const std::vector<AttachmentInfo>& colors, const AttachmentInfo* depth,
                const DeviceLimits& limits);
// Per-draw checks: inline fast paths, the message is built out of line only on failure.
[[noreturn]] void bufferRangeFailed(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what);
inline void bufferRange(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what) {
    if (offset > d.size || size > d.size - offset) [[unlikely]]
        bufferRangeFailed(d, offset, size, what);
}

// Bit set of slots a pipeline declares; draw/dispatch checks every declared slot is bound.
uint64_t requiredSlotMask(const std::vector<BindingSlot>& bindings);
[[noreturn]] void missingBindingsFailed(uint64_t missing, const char* pipelineName);
inline void missingBindings(uint64_t required, uint64_t bound, const char* pipelineName) {
    if (const uint64_t missing = required & ~bound) [[unlikely]]
        missingBindingsFailed(missing, pipelineName);
}

}  // namespace fe::gdi::validate
