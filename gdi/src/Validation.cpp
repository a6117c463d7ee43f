#include "fe/gdi/Validation.h"

#include <algorithm>
#include <string>

namespace fe::gdi::validate {

namespace {
std::string label(const char* kind, const char* name) {
    return std::string(kind) + (name && *name ? std::string(" '") + name + "'" : std::string());
}
[[noreturn]] void fail(const std::string& what, const std::string& why) { throw Error(what + ": " + why); }
}  // namespace

void bufferDesc(const BufferDesc& d) {
    const std::string what = label("buffer", d.debugName);
    if (d.size == 0) fail(what, "size is 0 (a buffer needs at least one byte)");
    if (d.size > (uint64_t(1) << 40)) fail(what, "size " + std::to_string(d.size) + " bytes is out of range");
    if (d.usage == BufferUsage::None) fail(what, "usage is None");
}

void textureDesc(const TextureDesc& d, const DeviceLimits& limits) {
    const std::string what = label("texture", d.debugName);
    if (d.format == Format::Undefined || d.format >= Format::Count) fail(what, "format is undefined");
    if (d.width == 0 || d.height == 0)
        fail(what, "size " + std::to_string(d.width) + "x" + std::to_string(d.height) + " has a zero dimension");
    if (limits.maxTextureSize2D && (d.width > limits.maxTextureSize2D || d.height > limits.maxTextureSize2D))
        fail(what, "size " + std::to_string(d.width) + "x" + std::to_string(d.height) + " exceeds the device limit " +
                       std::to_string(limits.maxTextureSize2D));
    uint32_t maxMips = 1;
    for (uint32_t s = std::max(d.width, d.height); s > 1; s >>= 1) ++maxMips;
    if (d.mipLevels == 0 || d.mipLevels > maxMips)
        fail(what, "mipLevels " + std::to_string(d.mipLevels) + " not in [1, " + std::to_string(maxMips) + "]");
    if (d.usage == TextureUsage::None) fail(what, "usage is None");
    if (isDepthFormat(d.format) && any(d.usage, TextureUsage::Storage))
        fail(what, "depth format " + std::string(formatInfo(d.format).name) + " cannot be a storage texture");
}

void presentTexture(const TextureDesc& d, const std::string& name) {
    const std::string what = "present: texture" + (name.empty() ? std::string() : " '" + name + "'");
    if (d.format != Format::RGBA8 && d.format != Format::RGBA8_SRGB)
        fail(what, "format " + std::string(formatInfo(d.format).name) + " cannot be shown; present RGBA8 or RGBA8_SRGB");
    if (!any(d.usage, TextureUsage::CopySrc)) fail(what, "needs CopySrc usage (present copies it into the window)");
}

void samplerDesc(const SamplerDesc& d) {
    if (!(d.maxAnisotropy >= 1.0f && d.maxAnisotropy <= 16.0f))
        fail(label("sampler", d.debugName), "maxAnisotropy must be in [1, 16]");
}

void shaderDesc(const ShaderDesc& d) {
    const std::string what = label("shader", d.binary.name);
    if (d.stage != ShaderStage::Vertex && d.stage != ShaderStage::Fragment && d.stage != ShaderStage::Compute)
        fail(what, "stage must be exactly one of Vertex, Fragment, Compute");
    if (!d.entryPoint || !*d.entryPoint) fail(what, "entry point is empty");
}

static void bindingList(const std::vector<BindingSlot>& bindings, const std::string& what) {
    uint64_t seen = 0;
    for (const BindingSlot& b : bindings) {
        if (b.slot >= 64) fail(what, "binding slot " + std::to_string(b.slot) + " is out of range (0..63)");
        if (seen & (uint64_t(1) << b.slot)) fail(what, "binding slot " + std::to_string(b.slot) + " is declared twice");
        seen |= uint64_t(1) << b.slot;
    }
}

void graphicsPipelineDesc(const GraphicsPipelineDesc& d, const DeviceLimits& limits) {
    const std::string what = label("graphics pipeline", d.debugName);
    if (!d.vertexShader) fail(what, "no vertex shader");
    if (d.colorFormats.empty() && d.depthFormat == Format::Undefined) fail(what, "no colour or depth target format");
    if (limits.maxColorAttachments && d.colorFormats.size() > limits.maxColorAttachments)
        fail(what, std::to_string(d.colorFormats.size()) + " colour targets exceed the device limit " +
                       std::to_string(limits.maxColorAttachments));
    for (Format f : d.colorFormats)
        if (f == Format::Undefined || isDepthFormat(f))
            fail(what, "colour target format " + std::string(formatInfo(f).name) + " is not a colour format");
    if (d.depthFormat != Format::Undefined && !isDepthFormat(d.depthFormat))
        fail(what, "depth format " + std::string(formatInfo(d.depthFormat).name) + " is not a depth format");
    if ((d.depthStencil.depthTest || d.depthStencil.depthWrite) && d.depthFormat == Format::Undefined)
        fail(what, "depth test/write enabled without a depth format");
    if (d.depthStencil.stencilTest && !formatInfo(d.depthFormat).hasStencil)
        fail(what, "stencil test enabled but depth format has no stencil");
    if (d.blend.size() > d.colorFormats.size()) fail(what, "more blend states than colour targets");
    uint32_t locations = 0;
    for (size_t i = 0; i < d.vertexBuffers.size(); ++i) {
        const VertexBufferLayout& vb = d.vertexBuffers[i];
        if (vb.stride == 0) fail(what, "vertex buffer " + std::to_string(i) + " has stride 0");
        for (const VertexAttribute& a : vb.attributes) {
            if (a.format >= VertexFormat::Count) fail(what, "vertex attribute has an invalid format");
            if (a.location >= 16) fail(what, "vertex attribute location " + std::to_string(a.location) + " >= 16");
            if (locations & (1u << a.location))
                fail(what, "vertex attribute location " + std::to_string(a.location) + " is used twice");
            locations |= 1u << a.location;
            if (a.offset + vertexFormatInfo(a.format).bytes > vb.stride)
                fail(what, "vertex attribute at location " + std::to_string(a.location) + " overruns stride " +
                               std::to_string(vb.stride));
        }
    }
    bindingList(d.bindings, what);
}

void computePipelineDesc(const ComputePipelineDesc& d) {
    const std::string what = label("compute pipeline", d.debugName);
    if (!d.computeShader) fail(what, "no compute shader");
    bindingList(d.bindings, what);
}

Rect renderPass(const RenderPassDesc& d, const std::vector<AttachmentInfo>& colors, const AttachmentInfo* depth,
                const DeviceLimits& limits) {
    const std::string what = label("render pass", d.debugName);
    if (colors.empty() && !depth) fail(what, "no attachments");
    if (limits.maxColorAttachments && colors.size() > limits.maxColorAttachments)
        fail(what, std::to_string(colors.size()) + " colour attachments exceed the device limit");
    uint32_t w = 0, h = 0;
    auto check = [&](const AttachmentInfo& a, const std::string& name) {
        if (!any(a.usage, TextureUsage::RenderTarget)) fail(what, name + " texture lacks RenderTarget usage");
        if (w == 0 && h == 0) { w = a.width; h = a.height; }
        else if (a.width != w || a.height != h)
            fail(what, "mismatched attachments: " + name + " is " + std::to_string(a.width) + "x" +
                           std::to_string(a.height) + ", others are " + std::to_string(w) + "x" + std::to_string(h));
    };
    for (size_t i = 0; i < colors.size(); ++i) {
        if (isDepthFormat(colors[i].format)) fail(what, "colour attachment " + std::to_string(i) + " has a depth format");
        check(colors[i], "colour attachment " + std::to_string(i));
    }
    if (depth) {
        if (!isDepthFormat(depth->format)) fail(what, "depth attachment has colour format " + std::string(formatInfo(depth->format).name));
        check(*depth, "depth attachment");
    }
    return Rect{0, 0, w, h};
}

void bufferRangeFailed(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what) {
    fail(label("buffer", d.debugName), std::string(what) + ": range [" + std::to_string(offset) + ", " +
                                           std::to_string(offset + size) + ") exceeds its size " + std::to_string(d.size));
}

void bindingRangeFailed(const BufferDesc& d, uint64_t offset, uint64_t size, const char* what) {
    if (size == 0 && offset <= d.size)
        fail(label("buffer", d.debugName), std::string(what) + ": empty range (offset " + std::to_string(offset) +
                                               " is the end of the buffer)");
    bufferRangeFailed(d, offset, size, what);
}

namespace {
const char* kindName(BindingType t) {
    switch (t) {
        case BindingType::UniformBuffer: return "a uniform buffer";
        case BindingType::StorageBuffer: return "a storage buffer";
        case BindingType::SampledTexture: return "a sampled texture";
        case BindingType::StorageTexture: return "a storage texture";
    }
    return "?";
}
}  // namespace

void wrongBindingKindFailed(uint32_t slot, BindingType expected, BindingType bound, const char* pipelineName) {
    fail(label("draw/dispatch with pipeline", pipelineName), "slot " + std::to_string(slot) + " expects " +
                                                                 kindName(expected) + " but " + kindName(bound) + " is bound");
}

std::array<uint8_t, 64> slotKinds(const std::vector<BindingSlot>& bindings) {
    std::array<uint8_t, 64> kinds{};
    for (const BindingSlot& b : bindings) kinds[b.slot & 63] = uint8_t(1 + uint8_t(b.type));
    return kinds;
}

uint64_t requiredSlotMask(const std::vector<BindingSlot>& bindings) {
    uint64_t m = 0;
    for (const BindingSlot& b : bindings) m |= uint64_t(1) << (b.slot & 63);
    return m;
}

void missingBindingsFailed(uint64_t missing, const char* pipelineName) {
    std::string slots;
    for (int i = 0; i < 64; ++i)
        if (missing & (uint64_t(1) << i)) slots += (slots.empty() ? "" : ", ") + std::to_string(i);
    fail(label("draw/dispatch with pipeline", pipelineName), "missing binding for slot(s) " + slots);
}

}  // namespace fe::gdi::validate
