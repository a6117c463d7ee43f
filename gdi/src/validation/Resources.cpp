// Shared validation: Descriptions of buffers, textures, views and samplers; subresources, uploads and usages.
#include "ValidationSupport.h"

namespace fe::gdi::validate {

void bufferDesc(const BufferDesc& d, const DeviceLimits& limits) {
    const std::string what = label("buffer", d.debugName);
    if (d.size == 0) fail(what, "size is 0 (a buffer needs at least one byte)");
    if (d.size > (uint64_t(1) << 40))
        fail(what, "size " + std::to_string(d.size) + " bytes is out of range");
    if (d.usage == BufferUsage::None) fail(what, "usage is None");
    allocationFits(what, d.size, limits);
}

void initialData(const BufferDesc& d, uint64_t size) {
    if (size != 0 && size != d.size)
        fail(label("buffer", d.debugName), "initial data is " + std::to_string(size) +
                                               " bytes, the buffer " + std::to_string(d.size) +
                                               " (they must match)");
}

void textureDesc(const TextureDesc& d, const DeviceInfo& device) {
    const std::string what = label("texture", d.debugName);
    const DeviceLimits& limits = device.limits;
    using D = TextureDimension;
    if (d.dimension > D::Texture3D) fail(what, "dimension is invalid");
    if (d.format == Format::Undefined || d.format >= Format::Count)
        fail(what, "format is undefined");
    for (Format f : d.viewFormats)
        if (!viewFormatsCompatible(d.format, f))
            fail(what, "view format " + std::string(formatInfo(f).name) +
                           " is not compatible with " + std::string(formatInfo(d.format).name) +
                           " (its sRGB/UNORM pair, the same texel size, or between RGBA8 and "
                           "BGRA8)");
    const std::string kind = textureDimensionName(d.dimension);
    const std::string size = std::to_string(d.width) + "x" + std::to_string(d.height) + "x" +
                             std::to_string(d.depthOrLayers);
    if (d.width == 0 || d.height == 0 || d.depthOrLayers == 0)
        fail(what, "size " + size + " has a zero dimension");
    const uint32_t maxEdge = d.dimension == D::Texture3D ? limits.maxTextureSize3D
                             : isCube(d.dimension)       ? limits.maxTextureSizeCube
                                                         : limits.maxTextureSize2D;
    if (maxEdge && (d.width > maxEdge || d.height > maxEdge ||
                    (d.dimension == D::Texture3D && d.depthOrLayers > maxEdge)))
        fail(what, kind + " size " + size + " exceeds the device limit " + std::to_string(maxEdge));
    switch (d.dimension) {
        case D::Texture2D:
            if (d.depthOrLayers != 1)
                fail(what,
                     "a Texture2D has depthOrLayers 1, got " + std::to_string(d.depthOrLayers));
            break;
        case D::TextureCube:
        case D::TextureCubeArray:
            if (d.width != d.height) fail(what, kind + " faces must be square, got " + size);
            if (d.dimension == D::TextureCube && d.depthOrLayers != 6)
                fail(what, "a TextureCube has 6 layers, got " + std::to_string(d.depthOrLayers));
            if (d.depthOrLayers % 6)
                fail(what, "a TextureCubeArray has 6 layers per cube, got " +
                               std::to_string(d.depthOrLayers));
            if (d.dimension == D::TextureCubeArray && !device.features.textureCubeArray)
                fail(what, "cube map arrays are not supported on " + device.backend);
            [[fallthrough]];
        case D::Texture2DArray:
            if (limits.maxTextureArrayLayers && d.depthOrLayers > limits.maxTextureArrayLayers)
                fail(what, std::to_string(d.depthOrLayers) + " layers exceed the device limit " +
                               std::to_string(limits.maxTextureArrayLayers));
            break;
        case D::Texture3D:
            if (isDepthFormat(d.format)) fail(what, "a Texture3D cannot have a depth format");
            break;
    }
    uint32_t maxMips = 1;
    uint32_t edge = std::max(d.width, d.height);
    if (d.dimension == D::Texture3D) edge = std::max(edge, d.depthOrLayers);
    for (uint32_t s = edge; s > 1; s >>= 1) ++maxMips;
    if (d.mipLevels == 0 || d.mipLevels > maxMips)
        fail(what, "mipLevels " + std::to_string(d.mipLevels) + " not in [1, " +
                       std::to_string(maxMips) + "]");
    if (d.usage == TextureUsage::None) fail(what, "usage is None");
    if (any(d.usage, TextureUsage::Transient) &&
        (d.usage != (TextureUsage::Transient | TextureUsage::RenderTarget) || d.mipLevels != 1))
        fail(what,
             "a Transient texture is a RenderTarget only (no Sampled, Storage, CopySrc or "
             "CopyDst usage) of one mip level: its contents live inside one render pass");
    if ((d.format == Format::BGRA8 || d.format == Format::BGRA8_SRGB) &&
        any(d.usage, TextureUsage::Storage))
        fail(what, std::string(formatInfo(d.format).name) +
                       " cannot be a storage texture (no shader image format names it)");
    if (isDepthFormat(d.format) && any(d.usage, TextureUsage::Storage))
        fail(what, "depth format " + std::string(formatInfo(d.format).name) +
                       " cannot be a storage texture");
    if (isCompressedFormat(d.format)) {
        if (!device.features.textureCompressionBC)
            fail(what, "block-compressed format " + std::string(formatInfo(d.format).name) +
                           " is not supported on " + device.backend);
        if (any(d.usage, TextureUsage::RenderTarget | TextureUsage::Storage))
            fail(what, "block-compressed format " + std::string(formatInfo(d.format).name) +
                           " can only be sampled and copied (no RenderTarget or Storage usage)");
        if (d.dimension == D::Texture3D)
            fail(what, "block-compressed 3D textures are not supported");
    }
    const uint32_t s = d.sampleCount;
    if (s != 1 && s != 2 && s != 4 && s != 8)
        fail(what, "sampleCount " + std::to_string(s) + " is not 1, 2, 4 or 8");
    if (s > 1) {
        const uint32_t supported =
            isDepthFormat(d.format) ? limits.depthSampleCounts : limits.colorSampleCounts;
        if (!(supported & s))
            fail(what, std::to_string(s) + " samples are not supported for " +
                           std::string(isDepthFormat(d.format) ? "depth" : "colour") +
                           " targets on " + device.backend);
        if (d.dimension != D::Texture2D || d.mipLevels != 1)
            fail(what, "a multisampled texture is a Texture2D with one mip level");
        if (!any(d.usage, TextureUsage::RenderTarget) || any(d.usage, TextureUsage::Storage))
            fail(what,
                 "a multisampled texture is a render target (resolved into a single-sample "
                 "one, or read per sample by sampler2DMS with Sampled usage), not storage");
        if (isCompressedFormat(d.format)) fail(what, "a compressed format cannot be multisampled");
    }
    uint64_t bytes = 0;
    for (uint32_t mip = 0; mip < d.mipLevels; ++mip)
        bytes += textureByteSize(d, mip) * mipExtent(d, mip).depthOrLayers;
    allocationFits(what, bytes * s, limits);
}

Extent3 mipExtent(const TextureDesc& d, uint32_t mip) {
    Extent3 e{std::max(1u, d.width >> mip), std::max(1u, d.height >> mip), d.depthOrLayers};
    if (d.dimension == TextureDimension::Texture3D)
        e.depthOrLayers = std::max(1u, d.depthOrLayers >> mip);
    return e;
}

TextureDesc textureView(const TextureDesc& t, const std::string& name, bool textureIsView,
                        const TextureViewDesc& v) {
    const std::string what =
        "texture view '" + std::string(v.debugName ? v.debugName : "") + "' of '" + name + "'";
    if (textureIsView) fail(what, "a view of a view: make it from the texture");
    if (t.sampleCount > 1) fail(what, "multisampled textures have no views");
    using D = TextureDimension;
    const D kind = v.dimension.value_or(t.dimension);
    const Format format = v.format == Format::Undefined ? t.format : v.format;
    if (format != t.format &&
        std::find(t.viewFormats.begin(), t.viewFormats.end(), format) == t.viewFormats.end())
        fail(what, std::string("format ") + std::string(formatInfo(format).name) +
                       " is not the texture's " + std::string(formatInfo(t.format).name) +
                       " nor in its TextureDesc::viewFormats");
    if (v.baseMip >= t.mipLevels || v.mipCount > t.mipLevels - v.baseMip)
        fail(what, "mips " + std::to_string(v.baseMip) + " + " + std::to_string(v.mipCount) +
                       " exceed the texture's " + std::to_string(t.mipLevels));
    const bool is3D = t.dimension == D::Texture3D;
    const bool allowed =
        is3D ? kind == D::Texture3D
             : kind != D::Texture3D && (t.dimension != D::Texture2D || kind == D::Texture2D ||
                                        kind == D::Texture2DArray);
    if (!allowed)
        fail(what, std::string("a ") + textureDimensionName(t.dimension) + " cannot be seen as a " +
                       textureDimensionName(kind));
    const uint32_t layers = is3D ? 1 : t.depthOrLayers;
    if (is3D && (v.baseLayer || v.layerCount > 1))
        fail(what, "a 3D view takes every slice (baseLayer and layerCount 0)");
    if (v.baseLayer >= layers || v.layerCount > layers - v.baseLayer)
        fail(what, "layers " + std::to_string(v.baseLayer) + " + " + std::to_string(v.layerCount) +
                       " exceed the texture's " + std::to_string(layers));
    const uint32_t count = v.layerCount ? v.layerCount : layers - v.baseLayer;
    if (kind == D::Texture2D && count != 1)
        fail(what, "a Texture2D view has one layer, not " + std::to_string(count));
    if ((kind == D::TextureCube && count != 6) || (kind == D::TextureCubeArray && count % 6))
        fail(what, std::string("a ") + textureDimensionName(kind) +
                       " view takes 6 layers per cube, not " + std::to_string(count));
    if (isCube(kind) && t.width != t.height) fail(what, "a cube view needs a square texture");
    TextureDesc d = t;
    d.dimension = kind;
    d.format = format;
    const Extent3 e = mipExtent(t, v.baseMip);
    d.width = e.width, d.height = e.height;
    d.depthOrLayers = is3D ? e.depthOrLayers : count;
    d.mipLevels = v.mipCount ? v.mipCount : t.mipLevels - v.baseMip;
    d.heap = {}, d.heapOffset = 0;
    d.viewFormats.clear();
    d.debugName = nullptr;
    if (!identitySwizzle(
            v.swizzle)) {  // Vulkan: swizzled views are sampled, never attachments or storage
        if (!any(t.usage, TextureUsage::Sampled))
            fail(what, "a swizzled view is sampled, and the texture has no Sampled usage");
        d.usage = TextureUsage::Sampled;
    }
    if (channelOrdersDiffer(t.format, format)) {  // GL swaps red and blue by the view's swizzle
        if (!any(t.usage, TextureUsage::Sampled))
            fail(what,
                 "a view between RGBA and BGRA channel orders is sampled only, and the "
                 "texture has no Sampled usage");
        d.usage = TextureUsage::Sampled;
    }
    return d;
}

void viewsAlive(const std::string& name, uint32_t views) {
    fail("destroy " + label("texture", name.c_str()),
         std::to_string(views) + " view(s) of it are alive: destroy them first");
}

void notAView(bool isView, const std::string& name, const char* what) {
    if (isView)
        fail(what, label("texture view", name.c_str()) +
                       " is for binding: copies, uploads, readback, mip generation "
                       "and barriers take its texture");
}

void subresource(const TextureDesc& d, Subresource at, const char* what, const std::string& name) {
    const std::string w = std::string(what) + ": " + label("texture", name.c_str());
    if (at.mipLevel >= d.mipLevels)
        fail(w, "mip level " + std::to_string(at.mipLevel) + " out of range (" +
                    std::to_string(d.mipLevels) + " levels)");
    const uint32_t layers = mipExtent(d, at.mipLevel).depthOrLayers;
    if (at.layer >= layers)
        fail(w, std::string(d.dimension == TextureDimension::Texture3D ? "slice " : "layer ") +
                    std::to_string(at.layer) + " out of range (" + std::to_string(layers) +
                    " at mip " + std::to_string(at.mipLevel) + ")");
}

void readable(const TextureDesc& d, Subresource at, const char* what, const std::string& name) {
    subresource(d, at, what, name);
    const std::string w = std::string(what) + ": " + label("texture", name.c_str());
    transientContents(d, w);
    if (d.sampleCount > 1)
        fail(w, "is multisampled: resolve it into a single-sample texture to read it");
    if (isCompressedFormat(d.format)) fail(w, "block-compressed textures cannot be read back");
}

void transientContents(const TextureDesc& d, const std::string& what) {
    if (any(d.usage, TextureUsage::Transient))
        fail(what, "is Transient: its contents live only inside a render pass");
}

void mipGeneration(const TextureDesc& d, const std::string& name) {
    const std::string w = "generateMips: " + label("texture", name.c_str());
    const FormatInfo& f = formatInfo(d.format);
    if (f.hasDepth || f.isInteger || isCompressedFormat(d.format))
        fail(w, "format " + std::string(f.name) + " cannot be filtered into mip levels");
    if (d.sampleCount > 1) fail(w, "is multisampled");
}

void uploadSize(const TextureDesc& d, Subresource at, uint64_t size, const char* what,
                const std::string& name) {
    subresource(d, at, what, name);
    transientContents(d, std::string(what) + ": " + label("texture", name.c_str()));
    const Extent3 e = mipExtent(d, at.mipLevel);
    const uint64_t expected = imageByteSize(d.format, e.width, e.height);
    if (size != expected)
        fail(std::string(what) + ": " + label("texture", name.c_str()),
             "mip " + std::to_string(at.mipLevel) + " layer " + std::to_string(at.layer) +
                 " needs " + std::to_string(expected) + " bytes, got " + std::to_string(size));
}

void presentTexture(const TextureDesc& d, const std::string& name) {
    const std::string what =
        "present: texture" + (name.empty() ? std::string() : " '" + name + "'");
    if (d.format != Format::RGBA8 && d.format != Format::RGBA8_SRGB && d.format != Format::BGRA8 &&
        d.format != Format::BGRA8_SRGB)
        fail(what, "format " + std::string(formatInfo(d.format).name) +
                       " cannot be shown; present RGBA8, RGBA8_SRGB, BGRA8 or BGRA8_SRGB");
    if (!any(d.usage, TextureUsage::CopySrc))
        fail(what, "needs CopySrc usage (present copies it into the window)");
}

void samplerDesc(const SamplerDesc& d) {
    if (!(d.maxAnisotropy >= 1.0f && d.maxAnisotropy <= 16.0f))
        fail(label("sampler", d.debugName), "maxAnisotropy must be in [1, 16]");
    if (d.compare > CompareOp::Always) fail(label("sampler", d.debugName), "compare op is invalid");
    if (!(d.lodBias >= -16.0f && d.lodBias <= 16.0f))
        fail(label("sampler", d.debugName), "lodBias must be in [-16, 16]");
    if (!(d.minLod >= 0.0f && d.minLod <= d.maxLod))
        fail(label("sampler", d.debugName),
             "minLod and maxLod must satisfy 0 <= minLod <= maxLod (and be numbers)");
    if (d.borderColor > BorderColor::OpaqueWhite)
        fail(label("sampler", d.debugName), "border colour is invalid");
    if (d.addressU > AddressMode::ClampToBorder || d.addressV > AddressMode::ClampToBorder ||
        d.addressW > AddressMode::ClampToBorder)
        fail(label("sampler", d.debugName), "address mode is invalid");
}

void unsupportedTextureUsage(const TextureDesc& d) {
    fail(label("texture", d.debugName),
         "format " + std::string(formatInfo(d.format).name) + " does not support usage " +
             textureUsageNames(d.usage) +
             " on this device (Device::formatCaps says what it can do)");
}

void mappable(const BufferDesc& d, const std::string& name) {
    if (d.access == MemoryAccess::GpuOnly)
        throw Error(
            "map: " + describeObject("buffer", name, {}) +
            " is GpuOnly; only Upload and Readback buffers can be mapped (use writeBuffer or a copy)");
}

void bufferUsage(const BufferDesc& d, BufferUsage usage, const std::string& name,
                 const char* what) {
    if (any(d.usage, usage)) return;
    throw Error(std::string(what) + ": " + label("buffer", name.c_str()) + " lacks " +
                bufferUsageNames(usage, " or ") + " usage (it was created with " +
                bufferUsageNames(d.usage) + ")");
}

void textureUsage(const TextureDesc& d, TextureUsage usage, const std::string& name,
                  const char* what) {
    if (any(d.usage, usage)) return;
    throw Error(std::string(what) + ": " + label("texture", name.c_str()) + " lacks " +
                textureUsageNames(usage, " or ") + " usage (it was created with " +
                textureUsageNames(d.usage) + ")");
}

void destroyedHandle(const char* kind, uint32_t id) {
    throw Error(std::string("destroy: ") + kind + " handle " + std::to_string(id) +
                " is not live (destroyed already, or made by another device)");
}

}  // namespace fe::gdi::validate

uint64_t fe::gdi::textureByteSize(const TextureDesc& d, uint32_t mipLevel) {
    const validate::Extent3 e = validate::mipExtent(d, mipLevel);
    return imageByteSize(d.format, e.width, e.height);
}
