// Layer 2 (GDI abstraction): checks every backend runs on descriptions before touching the
// native API, so invalid input gives the same clear message on Vulkan and GL.
#pragma once
#include <array>

#include "fe/gdi/Device.h"

namespace fe::gdi::validate {

// Each throws Error naming the object (debugName when set) and what is wrong.
void bufferDesc(const BufferDesc& d);
void textureDesc(const TextureDesc& d, const DeviceLimits& limits);
void samplerDesc(const SamplerDesc& d);
void shaderDesc(const ShaderDesc& d);
void graphicsPipelineDesc(const GraphicsPipelineDesc& d, const DeviceLimits& limits);
void computePipelineDesc(const ComputePipelineDesc& d);
// Device::present's texture: RGBA8 or RGBA8_SRGB (the bytes a window shows unchanged) with
// CopySrc usage, on every windowed backend.
void presentTexture(const TextureDesc& d, const std::string& name);
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

// A range bound to a slot must also be non-empty (Vulkan and GL both reject zero-sized bindings).
[[noreturn]] void bindingRangeFailed(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what);
inline void bindingRange(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what) {
    if (offset >= d.size || size > d.size - offset || size == 0) [[unlikely]]
        bindingRangeFailed(d, offset, size, what);
}

// The per-object fast path's test, shared by the backends: slot below 64 and a non-empty range
// inside a buffer of bufferSize bytes (size 0: to the end). Returns the size to bind, or 0 when
// the arguments need the checked path (which gives the error, if any).
inline uint64_t plainBindingSize(uint32_t slot, uint64_t bufferSize, uint64_t offset, uint64_t size) {
    if (slot >= 64 || offset >= bufferSize) return 0;
    const uint64_t rest = bufferSize - offset;
    if (size == 0) return rest;
    return size <= rest ? size : 0;
}

// Bit set of slots a pipeline declares; draw/dispatch checks every declared slot is bound.
uint64_t requiredSlotMask(const std::vector<BindingSlot>& bindings);
[[noreturn]] void missingBindingsFailed(uint64_t missing, const char* pipelineName);
inline void missingBindings(uint64_t required, uint64_t bound, const char* pipelineName) {
    if (const uint64_t missing = required & ~bound) [[unlikely]]
        missingBindingsFailed(missing, pipelineName);
}
// A slot bound with another kind of resource than the pipeline declares for it.
[[noreturn]] void wrongBindingKindFailed(uint32_t slot, BindingType expected, BindingType bound, const char* pipelineName);
// Per-slot declared kind, 1 + BindingType (0: the pipeline does not use the slot).
std::array<uint8_t, 64> slotKinds(const std::vector<BindingSlot>& bindings);

}  // namespace fe::gdi::validate
