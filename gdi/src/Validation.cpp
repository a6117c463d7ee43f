#include "fe/gdi/Validation.h"

#include "fe/gdi/Faults.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace fe::gdi {
uint64_t textureByteSize(const TextureDesc& d, uint32_t mipLevel) {
    const validate::Extent3 e = validate::mipExtent(d, mipLevel);
    return imageByteSize(d.format, e.width, e.height);
}
}  // namespace fe::gdi

namespace fe::gdi::validate {

namespace {
std::string label(const char* kind, const char* name) {
    return std::string(kind) + (name && *name ? std::string(" '") + name + "'" : std::string());
}

// "A|B" for the usage an object has; "A or B" for the usages a call accepts (separator " or ").
template <class Usage>
std::string usageNames(Usage u, std::initializer_list<std::pair<Usage, const char*>> names, const char* separator) {
    std::string out;
    for (const auto& [bit, n] : names)
        if (any(u, bit)) out += (out.empty() ? "" : separator) + std::string(n);
    return out.empty() ? "None" : out;
}
std::string bufferUsageNames(BufferUsage u, const char* separator = "|") {
    using B = BufferUsage;
    return usageNames(u, {{B::Vertex, "Vertex"}, {B::Index, "Index"}, {B::Uniform, "Uniform"}, {B::Storage, "Storage"},
                          {B::CopySrc, "CopySrc"}, {B::CopyDst, "CopyDst"}, {B::Indirect, "Indirect"}},
                      separator);
}
std::string textureUsageNames(TextureUsage u, const char* separator = "|") {
    using T = TextureUsage;
    return usageNames(u, {{T::Sampled, "Sampled"}, {T::RenderTarget, "RenderTarget"}, {T::Storage, "Storage"},
                          {T::CopySrc, "CopySrc"}, {T::CopyDst, "CopyDst"}},
                      separator);
}
[[noreturn]] void fail(const std::string& what, const std::string& why) { throw Error(what + ": " + why); }
}  // namespace

namespace {
// Bytes beyond what one allocation of the device may take (0: no limit known).
void allocationFits(const std::string& what, uint64_t bytes, const DeviceLimits& limits) {
    if (limits.maxAllocationSize && bytes > limits.maxAllocationSize)
        fail(what, std::to_string(bytes) + " bytes exceed the device's maxAllocationSize (" +
                       std::to_string(limits.maxAllocationSize) + " bytes)");
}
}  // namespace

void bufferDesc(const BufferDesc& d, const DeviceLimits& limits) {
    const std::string what = label("buffer", d.debugName);
    if (d.size == 0) fail(what, "size is 0 (a buffer needs at least one byte)");
    if (d.size > (uint64_t(1) << 40)) fail(what, "size " + std::to_string(d.size) + " bytes is out of range");
    if (d.usage == BufferUsage::None) fail(what, "usage is None");
    allocationFits(what, d.size, limits);
}

void initialData(const BufferDesc& d, uint64_t size) {
    if (size != 0 && size != d.size)
        fail(label("buffer", d.debugName), "initial data is " + std::to_string(size) + " bytes, the buffer " +
                                               std::to_string(d.size) + " (they must match)");
}

void textureDesc(const TextureDesc& d, const DeviceInfo& device) {
    const std::string what = label("texture", d.debugName);
    const DeviceLimits& limits = device.limits;
    using D = TextureDimension;
    if (d.dimension > D::Texture3D) fail(what, "dimension is invalid");
    if (d.format == Format::Undefined || d.format >= Format::Count) fail(what, "format is undefined");
    for (Format f : d.viewFormats)
        if (!formatsCompatible(d.format, f))
            fail(what, "view format " + std::string(formatInfo(f).name) + " is not compatible with " +
                           std::string(formatInfo(d.format).name) + " (its sRGB/UNORM pair, or the same texel size)");
    const std::string kind = textureDimensionName(d.dimension);
    const std::string size = std::to_string(d.width) + "x" + std::to_string(d.height) + "x" + std::to_string(d.depthOrLayers);
    if (d.width == 0 || d.height == 0 || d.depthOrLayers == 0) fail(what, "size " + size + " has a zero dimension");
    const uint32_t maxEdge = d.dimension == D::Texture3D ? limits.maxTextureSize3D
                             : isCube(d.dimension)       ? limits.maxTextureSizeCube
                                                         : limits.maxTextureSize2D;
    if (maxEdge && (d.width > maxEdge || d.height > maxEdge || (d.dimension == D::Texture3D && d.depthOrLayers > maxEdge)))
        fail(what, kind + " size " + size + " exceeds the device limit " + std::to_string(maxEdge));
    switch (d.dimension) {
        case D::Texture2D:
            if (d.depthOrLayers != 1) fail(what, "a Texture2D has depthOrLayers 1, got " + std::to_string(d.depthOrLayers));
            break;
        case D::TextureCube:
        case D::TextureCubeArray:
            if (d.width != d.height) fail(what, kind + " faces must be square, got " + size);
            if (d.dimension == D::TextureCube && d.depthOrLayers != 6)
                fail(what, "a TextureCube has 6 layers, got " + std::to_string(d.depthOrLayers));
            if (d.depthOrLayers % 6) fail(what, "a TextureCubeArray has 6 layers per cube, got " + std::to_string(d.depthOrLayers));
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
        fail(what, "mipLevels " + std::to_string(d.mipLevels) + " not in [1, " + std::to_string(maxMips) + "]");
    if (d.usage == TextureUsage::None) fail(what, "usage is None");
    if (isDepthFormat(d.format) && any(d.usage, TextureUsage::Storage))
        fail(what, "depth format " + std::string(formatInfo(d.format).name) + " cannot be a storage texture");
    if (isCompressedFormat(d.format)) {
        if (!device.features.textureCompressionBC)
            fail(what, "block-compressed format " + std::string(formatInfo(d.format).name) + " is not supported on " +
                           device.backend);
        if (any(d.usage, TextureUsage::RenderTarget | TextureUsage::Storage))
            fail(what, "block-compressed format " + std::string(formatInfo(d.format).name) +
                           " can only be sampled and copied (no RenderTarget or Storage usage)");
        if (d.dimension == D::Texture3D) fail(what, "block-compressed 3D textures are not supported");
    }
    const uint32_t s = d.sampleCount;
    if (s != 1 && s != 2 && s != 4 && s != 8) fail(what, "sampleCount " + std::to_string(s) + " is not 1, 2, 4 or 8");
    if (s > 1) {
        const uint32_t supported = isDepthFormat(d.format) ? limits.depthSampleCounts : limits.colorSampleCounts;
        if (!(supported & s))
            fail(what, std::to_string(s) + " samples are not supported for " + std::string(isDepthFormat(d.format) ? "depth" : "colour") +
                           " targets on " + device.backend);
        if (d.dimension != D::Texture2D || d.mipLevels != 1)
            fail(what, "a multisampled texture is a Texture2D with one mip level");
        if (!any(d.usage, TextureUsage::RenderTarget) || any(d.usage, TextureUsage::Storage | TextureUsage::Sampled))
            fail(what, "a multisampled texture is a render target, resolved (not sampled) into a single-sample one");
        if (isCompressedFormat(d.format)) fail(what, "a compressed format cannot be multisampled");
    }
    uint64_t bytes = 0;
    for (uint32_t mip = 0; mip < d.mipLevels; ++mip) bytes += textureByteSize(d, mip) * mipExtent(d, mip).depthOrLayers;
    allocationFits(what, bytes * s, limits);
}

Extent3 mipExtent(const TextureDesc& d, uint32_t mip) {
    Extent3 e{std::max(1u, d.width >> mip), std::max(1u, d.height >> mip), d.depthOrLayers};
    if (d.dimension == TextureDimension::Texture3D) e.depthOrLayers = std::max(1u, d.depthOrLayers >> mip);
    return e;
}

TextureDesc textureView(const TextureDesc& t, const std::string& name, bool textureIsView, const TextureViewDesc& v) {
    const std::string what = "texture view '" + std::string(v.debugName ? v.debugName : "") + "' of '" + name + "'";
    if (textureIsView) fail(what, "a view of a view: make it from the texture");
    if (t.sampleCount > 1) fail(what, "multisampled textures have no views");
    using D = TextureDimension;
    const D kind = v.dimension.value_or(t.dimension);
    const Format format = v.format == Format::Undefined ? t.format : v.format;
    if (format != t.format && std::find(t.viewFormats.begin(), t.viewFormats.end(), format) == t.viewFormats.end())
        fail(what, std::string("format ") + std::string(formatInfo(format).name) + " is not the texture's " +
                       std::string(formatInfo(t.format).name) + " nor in its TextureDesc::viewFormats");
    if (v.baseMip >= t.mipLevels || v.mipCount > t.mipLevels - v.baseMip)
        fail(what, "mips " + std::to_string(v.baseMip) + " + " + std::to_string(v.mipCount) + " exceed the texture's " +
                       std::to_string(t.mipLevels));
    const bool is3D = t.dimension == D::Texture3D;
    const bool allowed = is3D ? kind == D::Texture3D
                              : kind != D::Texture3D && (t.dimension != D::Texture2D || kind == D::Texture2D || kind == D::Texture2DArray);
    if (!allowed)
        fail(what, std::string("a ") + textureDimensionName(t.dimension) + " cannot be seen as a " + textureDimensionName(kind));
    const uint32_t layers = is3D ? 1 : t.depthOrLayers;
    if (is3D && (v.baseLayer || v.layerCount > 1)) fail(what, "a 3D view takes every slice (baseLayer and layerCount 0)");
    if (v.baseLayer >= layers || v.layerCount > layers - v.baseLayer)
        fail(what, "layers " + std::to_string(v.baseLayer) + " + " + std::to_string(v.layerCount) + " exceed the texture's " +
                       std::to_string(layers));
    const uint32_t count = v.layerCount ? v.layerCount : layers - v.baseLayer;
    if (kind == D::Texture2D && count != 1) fail(what, "a Texture2D view has one layer, not " + std::to_string(count));
    if ((kind == D::TextureCube && count != 6) || (kind == D::TextureCubeArray && count % 6))
        fail(what, std::string("a ") + textureDimensionName(kind) + " view takes 6 layers per cube, not " + std::to_string(count));
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
    if (!identitySwizzle(v.swizzle)) {  // Vulkan: swizzled views are sampled, never attachments or storage
        if (!any(t.usage, TextureUsage::Sampled)) fail(what, "a swizzled view is sampled, and the texture has no Sampled usage");
        d.usage = TextureUsage::Sampled;
    }
    return d;
}

void viewsAlive(const std::string& name, uint32_t views) {
    fail("destroy " + label("texture", name.c_str()), std::to_string(views) + " view(s) of it are alive: destroy them first");
}

void notAView(bool isView, const std::string& name, const char* what) {
    if (isView)
        fail(what, label("texture view", name.c_str()) + " is for binding: copies, uploads, readback, mip generation "
                                                        "and barriers take its texture");
}

TextureRegion textureRegion(const TextureDesc& d, const TextureRegion& r, const std::string& name, const char* what) {
    const std::string w = std::string(what) + ": " + label("texture", name.c_str());
    if (d.sampleCount > 1) fail(w, "multisampled textures are not copied by region (resolve them in a pass)");
    if (isDepthFormat(d.format))
        fail(w, std::string(formatInfo(d.format).name) + " is a depth format: use the whole-subresource call");
    if (r.mipLevel >= d.mipLevels)
        fail(w, "mip level " + std::to_string(r.mipLevel) + " out of range (" + std::to_string(d.mipLevels) + " levels)");
    const Extent3 e = mipExtent(d, r.mipLevel);
    TextureRegion out = r;
    out.width = r.width ? r.width : (r.x < e.width ? e.width - r.x : 0);
    out.height = r.height ? r.height : (r.y < e.height ? e.height - r.y : 0);
    out.depth = r.depth ? r.depth : (r.z < e.depthOrLayers ? e.depthOrLayers - r.z : 0);
    auto beyond = [](uint32_t at, uint32_t n, uint32_t size) { return n == 0 || at >= size || n > size - at; };
    if (beyond(r.x, out.width, e.width) || beyond(r.y, out.height, e.height) || beyond(r.z, out.depth, e.depthOrLayers))
        fail(w, "region at (" + std::to_string(r.x) + ", " + std::to_string(r.y) + ", " + std::to_string(r.z) + ") of " +
                    std::to_string(out.width) + "x" + std::to_string(out.height) + "x" + std::to_string(out.depth) +
                    " is outside mip level " + std::to_string(r.mipLevel) + " (" + std::to_string(e.width) + "x" +
                    std::to_string(e.height) + "x" + std::to_string(e.depthOrLayers) + ")");
    const uint32_t block = formatInfo(d.format).blockSize;
    auto aligned = [&](uint32_t at, uint32_t n, uint32_t size) { return at % block == 0 && (n % block == 0 || at + n == size); };
    if (block > 1 && !(aligned(r.x, out.width, e.width) && aligned(r.y, out.height, e.height)))
        fail(w, "a compressed region starts on a 4x4 block and spans whole blocks (or reaches the edge)");
    return out;
}

ResolvedLayout texelLayout(Format f, const TextureRegion& region, const TexelLayout& l, const char* what) {
    const FormatInfo& fi = formatInfo(f);
    const bool compressed = fi.blockSize > 1;
    const uint32_t unit = compressed ? fi.bytesPerBlock : fi.bytesPerPixel;  // bytes per texel or block
    const uint32_t columns = (region.width + fi.blockSize - 1) / fi.blockSize;
    const uint32_t rows = (region.height + fi.blockSize - 1) / fi.blockSize;
    const uint64_t rowBytes = uint64_t(columns) * unit;
    ResolvedLayout r{l};
    r.layout.bytesPerRow = l.bytesPerRow ? l.bytesPerRow : uint32_t(rowBytes);
    r.layout.rowsPerImage = l.rowsPerImage ? l.rowsPerImage : rows;
    const std::string w = what;
    if (l.offset % 4 || l.offset % unit)
        fail(w, "offset " + std::to_string(l.offset) + " is not a multiple of 4 and of the texel size (" + std::to_string(unit) + ")");
    if (r.layout.bytesPerRow % unit || r.layout.bytesPerRow < rowBytes)
        fail(w, "bytesPerRow " + std::to_string(r.layout.bytesPerRow) + " is not a multiple of the texel size (" +
                    std::to_string(unit) + ") of at least one row (" + std::to_string(rowBytes) + ")");
    if (r.layout.rowsPerImage < rows)
        fail(w, "rowsPerImage " + std::to_string(r.layout.rowsPerImage) + " is less than the region's " + std::to_string(rows) + " rows");
    if (compressed && (r.layout.bytesPerRow != rowBytes || r.layout.rowsPerImage != rows))
        fail(w, "compressed texels are packed tightly (bytesPerRow and rowsPerImage 0)");
    r.end = l.offset + (uint64_t(region.depth - 1) * r.layout.rowsPerImage + (rows - 1)) * r.layout.bytesPerRow + rowBytes;
    return r;
}

// The usages a buffer <-> texture copy needs, by direction.
static void bufferTextureUsages(const TextureDesc& t, const std::string& textureName, const BufferDesc& b,
                                const std::string& bufferName, bool toTexture, const char* what) {
    textureUsage(t, toTexture ? TextureUsage::CopyDst : TextureUsage::CopySrc, textureName, what);
    bufferUsage(b, toTexture ? BufferUsage::CopySrc : BufferUsage::CopyDst, bufferName, what);
}

RegionCopy bufferTextureRegion(const TextureDesc& t, const std::string& name, const BufferDesc& b, const std::string& bufferName,
                               const TextureRegion& region, const TexelLayout& layout, bool toTexture, const char* what) {
    bufferTextureUsages(t, name, b, bufferName, toTexture, what);
    const TextureRegion r = textureRegion(t, region, name, what);
    const ResolvedLayout l = texelLayout(t.format, r, layout, what);
    bufferRange(b, l.layout.offset, l.end - l.layout.offset, what);
    return {r, l.layout};
}

void dataSpan(size_t size, uint64_t end, const char* what) {
    if (size < end)
        fail(what, std::to_string(size) + " bytes of data; the region and layout span " + std::to_string(end));
}

std::pair<TextureRegion, TextureRegion> textureCopy(const TextureDesc& dst, const std::string& dstName, TextureRegion dstAt,
                                                    bool sameTexture, const TextureDesc& src, const std::string& srcName,
                                                    const TextureRegion& srcRegion) {
    textureUsage(src, TextureUsage::CopySrc, srcName, "copyTexture source");
    textureUsage(dst, TextureUsage::CopyDst, dstName, "copyTexture destination");
    const TextureRegion s = textureRegion(src, srcRegion, srcName, "copyTexture source");
    if (!formatsCompatible(src.format, dst.format))
        fail("copyTexture", std::string(formatInfo(src.format).name) + " texels cannot be copied into " + std::string(formatInfo(dst.format).name) +
                                " (the same format, its sRGB/UNORM pair, or the same texel size)");
    if ((src.dimension == TextureDimension::Texture3D) != (dst.dimension == TextureDimension::Texture3D))
        fail("copyTexture", "between a 3D texture and a layered one");
    dstAt.width = s.width, dstAt.height = s.height, dstAt.depth = s.depth;
    const TextureRegion d = textureRegion(dst, dstAt, dstName, "copyTexture destination");
    auto apart = [](uint32_t a, uint32_t b, uint32_t n) { return a + n <= b || b + n <= a; };
    if (sameTexture && s.mipLevel == d.mipLevel &&
        !(apart(s.x, d.x, s.width) || apart(s.y, d.y, s.height) || apart(s.z, d.z, s.depth)))
        fail("copyTexture", "source and destination overlap in '" + srcName + "'");
    return {d, s};
}

void wholeTextureCopy(const TextureDesc& dst, const std::string& dstName, const TextureDesc& src,
                      const std::string& srcName, uint32_t mip) {
    textureUsage(src, TextureUsage::CopySrc, srcName, "copyTexture source");
    textureUsage(dst, TextureUsage::CopyDst, dstName, "copyTexture destination");
    if (dst.format != src.format || dst.width != src.width || dst.height != src.height || dst.dimension != src.dimension ||
        dst.depthOrLayers != src.depthOrLayers || dst.sampleCount != src.sampleCount)
        fail("copyTexture", "'" + srcName + "' and '" + dstName + "' differ in format, kind, size or samples");
    if (mip >= dst.mipLevels || mip >= src.mipLevels) fail("copyTexture", "mip level out of range");
}

void subresourceBufferCopy(const TextureDesc& t, const std::string& textureName, Subresource at, const BufferDesc& b,
                           const std::string& bufferName, uint64_t offset, bool toTexture, const char* what) {
    bufferTextureUsages(t, textureName, b, bufferName, toTexture, what);
    subresource(t, at, what, textureName);
    if (isDepthFormat(t.format)) fail(what, "depth formats are not supported");
    if (t.sampleCount > 1) fail(what, "multisampled textures are not supported");
    const Extent3 e = mipExtent(t, at.mipLevel);
    bufferRange(b, offset, imageByteSize(t.format, e.width, e.height), what);
    if (offset % 4) fail(what, "buffer offset must be a multiple of 4");
}

void subresource(const TextureDesc& d, Subresource at, const char* what, const std::string& name) {
    const std::string w = std::string(what) + ": " + label("texture", name.c_str());
    if (at.mipLevel >= d.mipLevels)
        fail(w, "mip level " + std::to_string(at.mipLevel) + " out of range (" + std::to_string(d.mipLevels) + " levels)");
    const uint32_t layers = mipExtent(d, at.mipLevel).depthOrLayers;
    if (at.layer >= layers)
        fail(w, std::string(d.dimension == TextureDimension::Texture3D ? "slice " : "layer ") + std::to_string(at.layer) +
                    " out of range (" + std::to_string(layers) + " at mip " + std::to_string(at.mipLevel) + ")");
}

void readable(const TextureDesc& d, Subresource at, const char* what, const std::string& name) {
    subresource(d, at, what, name);
    const std::string w = std::string(what) + ": " + label("texture", name.c_str());
    if (d.sampleCount > 1) fail(w, "is multisampled: resolve it into a single-sample texture to read it");
    if (isCompressedFormat(d.format)) fail(w, "block-compressed textures cannot be read back");
}

void mipGeneration(const TextureDesc& d, const std::string& name) {
    const std::string w = "generateMips: " + label("texture", name.c_str());
    const FormatInfo& f = formatInfo(d.format);
    if (f.hasDepth || f.isInteger || isCompressedFormat(d.format))
        fail(w, "format " + std::string(f.name) + " cannot be filtered into mip levels");
    if (d.sampleCount > 1) fail(w, "is multisampled");
}

void uploadSize(const TextureDesc& d, Subresource at, uint64_t size, const char* what, const std::string& name) {
    subresource(d, at, what, name);
    const Extent3 e = mipExtent(d, at.mipLevel);
    const uint64_t expected = imageByteSize(d.format, e.width, e.height);
    if (size != expected)
        fail(std::string(what) + ": " + label("texture", name.c_str()),
             "mip " + std::to_string(at.mipLevel) + " layer " + std::to_string(at.layer) + " needs " +
                 std::to_string(expected) + " bytes, got " + std::to_string(size));
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
    if (d.compare > CompareOp::Always) fail(label("sampler", d.debugName), "compare op is invalid");
    if (!(d.lodBias >= -16.0f && d.lodBias <= 16.0f)) fail(label("sampler", d.debugName), "lodBias must be in [-16, 16]");
    if (!(d.minLod >= 0.0f && d.minLod <= d.maxLod))
        fail(label("sampler", d.debugName), "minLod and maxLod must satisfy 0 <= minLod <= maxLod (and be numbers)");
    if (d.borderColor > BorderColor::OpaqueWhite) fail(label("sampler", d.debugName), "border colour is invalid");
    if (d.addressU > AddressMode::ClampToBorder || d.addressV > AddressMode::ClampToBorder ||
        d.addressW > AddressMode::ClampToBorder)
        fail(label("sampler", d.debugName), "address mode is invalid");
}

void indirect(const BufferDesc& d, const std::string& name, uint64_t offset, uint32_t drawCount, uint32_t stride,
              uint32_t recordSize, const DeviceFeatures& features, const char* what) {
    const std::string w = std::string(what) + ": " + label("buffer", name.c_str());
    if (!any(d.usage, BufferUsage::Indirect)) fail(w, "lacks Indirect usage");
    if (offset % 4) fail(w, "offset " + std::to_string(offset) + " is not a multiple of 4");
    if (drawCount > 1 && !features.multiDrawIndirect) fail(w, "drawCount > 1 needs multiDrawIndirect");
    if (drawCount > 1 && (stride < recordSize || stride % 4))
        fail(w, "stride " + std::to_string(stride) + " must be a multiple of 4 of at least " + std::to_string(recordSize));
    if (drawCount == 0) return;
    const uint64_t bytes = uint64_t(drawCount - 1) * stride + recordSize;
    if (offset > d.size || bytes > d.size - offset)
        fail(w, std::to_string(drawCount) + " record(s) from offset " + std::to_string(offset) + " exceed its size " +
                    std::to_string(d.size));
}

void shaderDesc(const ShaderDesc& d) {
    const std::string what = label("shader", d.binary.name);
    if (d.stage != ShaderStage::Vertex && d.stage != ShaderStage::Fragment && d.stage != ShaderStage::Compute)
        fail(what, "stage must be exactly one of Vertex, Fragment, Compute");
    if (!d.entryPoint || !*d.entryPoint) fail(what, "entry point is empty");
    if (d.binary.vulkan.empty() && d.binary.opengl.empty())
        fail(what, "the binary is empty (no SPIR-V for Vulkan or for OpenGL: fe_add_shaders and shaders::find make both)");
}

static void bindingList(const std::vector<BindingSlot>& bindings, const std::string& what) {
    uint64_t seen = 0;
    for (const BindingSlot& b : bindings) {
        if (b.slot >= 64) fail(what, "binding slot " + std::to_string(b.slot) + " is out of range (0..63)");
        if (seen & (uint64_t(1) << b.slot)) fail(what, "binding slot " + std::to_string(b.slot) + " is declared twice");
        seen |= uint64_t(1) << b.slot;
    }
}

void graphicsPipelineDesc(const GraphicsPipelineDesc& d, const DeviceInfo& device) {
    const DeviceLimits& limits = device.limits;
    const std::string what = label("graphics pipeline", d.debugName);
    const uint32_t samples = d.multisample.sampleCount;
    if (samples != 1 && samples != 2 && samples != 4 && samples != 8)
        fail(what, "sampleCount " + std::to_string(samples) + " is not 1, 2, 4 or 8");
    if (samples > 1 && !(limits.colorSampleCounts & limits.depthSampleCounts & samples))
        fail(what, std::to_string(samples) + " samples are not supported on " + device.backend);
    if (d.raster.depthClamp && !device.features.depthClamp) fail(what, "depth clamp is not supported on " + device.backend);
    if (d.raster.depthBiasClamp != 0 && !device.features.depthBiasClamp)
        fail(what, "depth bias clamp is not supported on " + device.backend);
    for (float v : {d.raster.depthBiasConstant, d.raster.depthBiasSlope, d.raster.depthBiasClamp})
        if (!std::isfinite(v)) fail(what, "depth bias values must be finite");
    for (Format f : d.colorFormats)
        if (isCompressedFormat(f)) fail(what, "colour target format " + std::string(formatInfo(f).name) + " is compressed");
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
    if ((d.depthStencil.depthTest || d.depthStencil.depthWrite) && !formatInfo(d.depthFormat).hasDepth)
        fail(what, "depth test or write enabled but the depth format has no depth");
    if (d.blend.size() > d.colorFormats.size()) fail(what, "more blend states than colour targets");
    blendConstant(d.blendConstant, what.c_str());
    if (d.primitiveRestart && d.topology != PrimitiveTopology::TriangleStrip && d.topology != PrimitiveTopology::LineStrip)
        fail(what, "primitiveRestart needs a strip topology (TriangleStrip or LineStrip)");
    if (d.vertexBuffers.size() > kMaxVertexBuffers)
        fail(what, std::to_string(d.vertexBuffers.size()) + " vertex buffers (at most " + std::to_string(kMaxVertexBuffers) + ")");
    uint32_t locations = 0;
    for (size_t i = 0; i < d.vertexBuffers.size(); ++i) {
        const VertexBufferLayout& vb = d.vertexBuffers[i];
        for (const VertexAttribute& a : vb.attributes) {
            if (a.format >= VertexFormat::Count) fail(what, "vertex attribute has an invalid format");
            if (a.location >= 16) fail(what, "vertex attribute location " + std::to_string(a.location) + " >= 16");
            if (locations & (1u << a.location))
                fail(what, "vertex attribute location " + std::to_string(a.location) + " is used twice");
            locations |= 1u << a.location;
            if (vb.stride != 0 && a.offset + vertexFormatInfo(a.format).bytes > vb.stride)  // 0: one element for all
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

AttachmentInfo attachment(const TextureDesc& d, uint32_t mipLevel, uint32_t layer, const char* what, const std::string& name) {
    subresource(d, {mipLevel, layer}, what, name);
    const Extent3 e = mipExtent(d, mipLevel);
    return {d.format, e.width, e.height, d.usage, d.sampleCount};
}

Rect renderPass(const RenderPassDesc& d, const std::vector<AttachmentInfo>& colors,
                const std::vector<AttachmentInfo>& colorResolves, const AttachmentInfo* depth,
                const AttachmentInfo* depthResolve, const DeviceLimits& limits) {
    const std::string what = label("render pass", d.debugName);
    if (colors.empty() && !depth) fail(what, "no attachments");
    if (limits.maxColorAttachments && colors.size() > limits.maxColorAttachments)
        fail(what, std::to_string(colors.size()) + " colour attachments exceed the device limit");
    uint32_t w = 0, h = 0, samples = 0;
    auto check = [&](const AttachmentInfo& a, const std::string& name) {
        if (!any(a.usage, TextureUsage::RenderTarget)) fail(what, name + " texture lacks RenderTarget usage");
        if (w == 0 && h == 0) { w = a.width; h = a.height; samples = a.samples; }
        else if (a.width != w || a.height != h)
            fail(what, "mismatched attachments: " + name + " is " + std::to_string(a.width) + "x" +
                           std::to_string(a.height) + ", others are " + std::to_string(w) + "x" + std::to_string(h));
        else if (a.samples != samples)
            fail(what, "mismatched sample counts: " + name + " has " + std::to_string(a.samples) + ", others " +
                           std::to_string(samples));
    };
    auto checkResolve = [&](const AttachmentInfo& src, const AttachmentInfo& dst, const std::string& name) {
        if (src.samples == 1) fail(what, name + " is single-sample: nothing to resolve");
        if (dst.samples != 1) fail(what, name + " resolve target must be single-sample");
        if (dst.format != src.format)
            fail(what, name + " resolve target format " + std::string(formatInfo(dst.format).name) + " differs from " +
                           std::string(formatInfo(src.format).name));
        if (dst.width != src.width || dst.height != src.height) fail(what, name + " resolve target size differs");
        if (!any(dst.usage, TextureUsage::RenderTarget)) fail(what, name + " resolve target lacks RenderTarget usage");
    };
    for (size_t i = 0; i < colors.size(); ++i) {
        const std::string name = "colour attachment " + std::to_string(i);
        if (isDepthFormat(colors[i].format)) fail(what, name + " has a depth format");
        check(colors[i], name);
        // NaN or infinity converts to a format's values differently per driver (and a unorm
        // target has no such value): a clear colour is finite.
        if (i < d.colors.size() && d.colors[i].load == LoadOp::Clear)
            for (float c : d.colors[i].clear)
                if (!std::isfinite(c)) fail(what, name + ": clear colour is not finite");
        if (i < colorResolves.size() && colorResolves[i].format != Format::Undefined)
            checkResolve(colors[i], colorResolves[i], name);
    }
    if (depth) {
        if (!isDepthFormat(depth->format)) fail(what, "depth attachment has colour format " + std::string(formatInfo(depth->format).name));
        check(*depth, "depth attachment");
        const float z = d.depth.clearDepth;  // Vulkan's VkClearDepthStencilValue rule
        if (d.depth.load == LoadOp::Clear && !(z >= 0.0f && z <= 1.0f))
            fail(what, "depth attachment: clearDepth " + std::to_string(z) + " is not in [0, 1]");
        if (depthResolve) checkResolve(*depth, *depthResolve, "depth attachment");
    }
    return Rect{0, 0, w, h};
}

void pipelineSamples(uint32_t pipelineSamples, uint32_t passSamples, const char* pipelineName) {
    if (pipelineSamples != passSamples) [[unlikely]]
        fail(label("setPipeline: pipeline", pipelineName), "rasterizes " + std::to_string(pipelineSamples) +
                                                               " sample(s) but the render pass has " +
                                                               std::to_string(passSamples));
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

std::array<uint8_t, 64> slotDimensions(std::initializer_list<const ShaderInterface*> shaders, const std::string& pipeline) {
    std::array<uint8_t, 64> dims{};
    for (const ShaderInterface* s : shaders) {
        if (!s) continue;
        for (const ShaderInterface::Binding& b : s->bindings) {
            if (b.slot >= 64 || !b.dimension) continue;
            if (dims[b.slot] && dims[b.slot] != b.dimension)
                fail(label("pipeline", pipeline.c_str()),
                     "slot " + std::to_string(b.slot) + " is a " + textureDimensionName(TextureDimension(dims[b.slot] - 1)) +
                         " in one stage and a " + textureDimensionName(TextureDimension(b.dimension - 1)) + " in another");
            dims[b.slot] = b.dimension;
        }
    }
    return dims;
}

void wrongTextureDimensionFailed(uint32_t slot, uint8_t expected, uint8_t bound, const char* pipelineName) {
    fail(label("pipeline", pipelineName),
         "slot " + std::to_string(slot) + " is declared a " + textureDimensionName(TextureDimension(expected - 1)) +
             " in its shader, but the texture bound there is a " + textureDimensionName(TextureDimension(bound - 1)) +
             " (bind a view of that kind: createTextureView with .dimension)");
}

void unsupportedTextureUsage(const TextureDesc& d) {
    fail(label("texture", d.debugName), "format " + std::string(formatInfo(d.format).name) + " does not support usage " +
                                            textureUsageNames(d.usage) + " on this device (Device::formatCaps says what it can do)");
}

void computeShaderStage(ShaderStage stage, const ComputePipelineDesc& d) {
    if (stage != ShaderStage::Compute) fail(label("compute pipeline", d.debugName), "computeShader is not a compute shader");
}

std::vector<VertexBinding> vertexBindings(const GraphicsPipelineDesc& d) {
    std::vector<VertexBinding> out;
    for (const VertexBufferLayout& vb : d.vertexBuffers) {
        VertexBinding b{.stride = vb.stride, .perInstance = vb.perInstance};
        for (const VertexAttribute& a : vb.attributes) b.extent = std::max(b.extent, a.offset + vertexFormatInfo(a.format).bytes);
        out.push_back(b);
    }
    return out;
}

void VertexInputs::setVertexBuffer(uint32_t index, const BufferDesc& d, const std::string& name, uint64_t offset) {
    if (index >= kMaxVertexBuffers)
        throw Error("setVertexBuffer: index " + std::to_string(index) + " out of range (at most " +
                    std::to_string(kMaxVertexBuffers) + " vertex buffers)");
    bufferUsage(d, BufferUsage::Vertex, name, "setVertexBuffer");
    if (offset >= d.size) bufferRange(d, offset, 1, "setVertexBuffer");
    buffers_[index] = {d.size - offset, name};
    bound_ |= 1u << index;
    update();
}

void VertexInputs::setIndexBuffer(const BufferDesc& d, const std::string& name, IndexType type, uint64_t offset) {
    bufferUsage(d, BufferUsage::Index, name, "setIndexBuffer");
    if (offset >= d.size) bufferRange(d, offset, 1, "setIndexBuffer");
    const uint32_t bytes = type == IndexType::U16 ? 2 : 4;
    if (offset % bytes)
        fail(label("buffer", name.c_str()), "setIndexBuffer: offset " + std::to_string(offset) + " is not a multiple of " +
                                                std::to_string(bytes) + " (the index size)");
    indexBound_ = true;
    indexOffset_ = offset;
    indexBytes_ = bytes;
    indices_ = (d.size - offset) / bytes;
    indexName_ = name;
}

void VertexInputs::setPipeline(const std::vector<VertexBinding>* bindings, const std::string* pipelineName) {
    bindings_ = bindings;
    pipelineName_ = pipelineName;
    required_ = bindings ? (1u << bindings->size()) - 1u : 0u;
    update();
}

void VertexInputs::clear() {
    bound_ = 0;
    indexBound_ = false;
    indices_ = 0;
    update();
}

void VertexInputs::update() {
    vertices_ = instances_ = ~uint64_t(0);
    if (!bindings_) return;
    for (uint32_t i = 0; i < bindings_->size(); ++i) {
        const VertexBinding& b = (*bindings_)[i];
        if (!(bound_ >> i & 1u) || b.stride == 0) continue;
        const uint64_t available = buffers_[i].available;
        const uint64_t elements = available < b.extent ? 0 : (available - b.extent) / b.stride + 1;
        uint64_t& capacity = b.perInstance ? instances_ : vertices_;
        capacity = std::min(capacity, elements);
    }
}

void VertexInputs::notReady(const char* what) const {
    const uint32_t missing = required_ & ~bound_;
    throw Error(std::string(what) + ": pipeline '" + (pipelineName_ ? *pipelineName_ : std::string()) +
                "' reads vertex buffer " + std::to_string(std::countr_zero(missing)) +
                ", which is not bound (setVertexBuffer)");
}

void VertexInputs::outside(const char* what, uint32_t count, uint32_t instanceCount, uint32_t first,
                           uint32_t firstInstance) const {
    const bool instances = uint64_t(firstInstance) + instanceCount > instances_;
    throw Error(std::string(what) + ": " + (instances ? "instances [" : "vertices [") +
                std::to_string(instances ? firstInstance : first) + ", " +
                std::to_string(instances ? uint64_t(firstInstance) + instanceCount : uint64_t(first) + count) +
                ") reach past the bound vertex buffers of pipeline '" + (pipelineName_ ? *pipelineName_ : std::string()) +
                "', which hold " + std::to_string(instances ? instances_ : vertices_));
}

void VertexInputs::indexedOutside(uint32_t count, uint32_t instanceCount, uint32_t first, uint32_t firstInstance) const {
    if (!indexBound_) throw Error("drawIndexed without an index buffer");
    if (uint64_t(first) + count > indices_)
        fail(label("buffer", indexName_.c_str()), "drawIndexed: indices [" + std::to_string(first) + ", " +
                                                      std::to_string(uint64_t(first) + count) +
                                                      ") reach past the index buffer, which holds " +
                                                      std::to_string(indices_) + " from offset " +
                                                      std::to_string(indexOffset_));
    outside("drawIndexed", 0, instanceCount, 0, firstInstance);
}

void VertexInputs::indexedIndirect(const char* what) const {
    if (!indexBound_) throw Error(std::string(what) + " without an index buffer");
    if (indexOffset_ != 0)
        throw Error(std::string(what) + ": the index buffer must be bound at offset 0 (records hold firstIndex)");
}

void badViewport(const Viewport& v, const ViewportLimits& l) {
    std::string why;
    if (!(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.width) && std::isfinite(v.height)))
        why = "not finite";
    else if (v.height < 0)
        why = "a negative height (Vulkan's y flip) is not supported: clip space is already Vulkan's, y down, on every "
              "backend; flip y in the projection instead";
    else if (!(v.width > 0 && v.height > 0))
        why = "width and height must be positive";
    else if (!(v.width <= l.maxSize && v.height <= l.maxSize))
        why = "width and height must be at most the device's maxViewportSize (" + std::to_string(uint64_t(l.maxSize)) + ")";
    else if (!(v.x >= l.lo && v.y >= l.lo && v.x + v.width <= l.hi && v.y + v.height <= l.hi))
        why = "x, y, x + width and y + height must lie within the device's viewportBounds [" + std::to_string(int64_t(l.lo)) +
              ", " + std::to_string(int64_t(l.hi)) + "]";
    else
        why = "minDepth and maxDepth must lie in [0, 1]";
    throw Error("setViewport {" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.width) + ", " +
                std::to_string(v.height) + ", " + std::to_string(v.minDepth) + ", " + std::to_string(v.maxDepth) + "}: " + why);
}

void badDispatch(uint32_t x, uint32_t y, uint32_t z, const DeviceLimits& l) {
    throw Error("dispatch(" + std::to_string(x) + ", " + std::to_string(y) + ", " + std::to_string(z) +
                "): beyond the device's maxComputeWorkGroupCount (" + std::to_string(l.maxComputeWorkGroupCount[0]) + ", " +
                std::to_string(l.maxComputeWorkGroupCount[1]) + ", " + std::to_string(l.maxComputeWorkGroupCount[2]) + ")");
}

void bufferCopy(const BufferDesc& dst, const std::string& dstName, uint64_t dstOffset, const BufferDesc& src,
                const std::string& srcName, uint64_t srcOffset, uint64_t size, bool sameBuffer) {
    bufferUsage(src, BufferUsage::CopySrc, srcName, "copyBuffer source");
    bufferUsage(dst, BufferUsage::CopyDst, dstName, "copyBuffer destination");
    bufferRange(dst, dstOffset, size, "copyBuffer destination");
    bufferRange(src, srcOffset, size, "copyBuffer source");
    if (sameBuffer && size && dstOffset < srcOffset + size && srcOffset < dstOffset + size)
        fail(label("buffer", dstName.c_str()), "copyBuffer: the source [" + std::to_string(srcOffset) + ", " +
                                                   std::to_string(srcOffset + size) + ") and destination [" +
                                                   std::to_string(dstOffset) + ", " + std::to_string(dstOffset + size) +
                                                   ") overlap");
}

void listOfDestroyedDevice(const char* what) {
    throw Error(std::string(what) + ": the device of this command list was destroyed (destroy lists before their device)");
}

void fenceNotIssued(FenceValue fence, FenceValue last, const char* what) {
    throw Error(std::string(what) + ": fence " + std::to_string(fence) + " was never issued (the last submission's is " +
                std::to_string(last) + ")");
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

namespace {
// A state the texture's usage and format allow. Undefined always (contents not needed), and the
// copy states always: the device's own transfers (writeTexture, readTexture) copy any texture,
// so "it was last written by writeTexture" is a true CopyDst whatever the usage.
void stateAllowed(const TextureDesc& d, ResourceState s, const std::string& name) {
    const bool depth = isDepthFormat(d.format);
    auto need = [&](TextureUsage u) { textureUsage(d, u, name, (std::string("barrier to or from ") + resourceStateName(s)).c_str()); };
    switch (s) {
        case ResourceState::Undefined: return;
        case ResourceState::RenderTarget:
        case ResourceState::DepthTarget:
            need(TextureUsage::RenderTarget);
            if (depth != (s == ResourceState::DepthTarget))
                throw Error("barrier: " + describeObject("texture", name, {}) + " has format " +
                            std::string(formatInfo(d.format).name) + ": its attachment state is " +
                            (depth ? "DepthTarget" : "RenderTarget"));
            return;
        case ResourceState::ShaderRead: return need(TextureUsage::Sampled | TextureUsage::Storage);
        case ResourceState::Storage: return need(TextureUsage::Storage);
        case ResourceState::CopySrc:
        case ResourceState::CopyDst: return;
    }
}

// Each access of a barrier needs the usage that allows it; the copy accesses need none (the
// device's writeBuffer and readBuffer copy any buffer, as for textures above).
void accessesAllowed(const BufferDesc& d, BufferAccess a, const std::string& name) {
    using A = BufferAccess;
    using U = BufferUsage;
    static constexpr std::pair<A, U> kNeeds[] = {{A::Vertex, U::Vertex},       {A::Index, U::Index},
                                                 {A::Indirect, U::Indirect},   {A::Uniform, U::Uniform},
                                                 {A::StorageRead, U::Storage}, {A::StorageWrite, U::Storage}};
    for (const auto& [access, usage] : kNeeds)
        if (any(a, access)) bufferUsage(d, usage, name, "barrier");
}
}  // namespace

SubresourceRange textureBarrier(const TextureDesc& d, const TextureBarrier& b, const std::string& name) {
    if (b.after == ResourceState::Undefined) throw Error("barrier: a texture cannot go to Undefined");
    stateAllowed(d, b.before, name);
    stateAllowed(d, b.after, name);
    const uint32_t layers = d.dimension == TextureDimension::Texture3D ? 1 : d.depthOrLayers;
    SubresourceRange r{b.baseMip, b.mipCount ? b.mipCount : d.mipLevels - std::min(b.baseMip, d.mipLevels), b.baseLayer,
                       b.layerCount ? b.layerCount : layers - std::min(b.baseLayer, layers)};
    if (b.baseMip >= d.mipLevels || r.mipCount == 0 || uint64_t(r.baseMip) + r.mipCount > d.mipLevels ||
        b.baseLayer >= layers || r.layerCount == 0 || uint64_t(r.baseLayer) + r.layerCount > layers)
        throw Error("barrier: " + describeObject("texture", name, {}) + " has mips 0-" + std::to_string(d.mipLevels - 1) +
                    " and layers 0-" + std::to_string(layers - 1) + "; the barrier names mips " + std::to_string(b.baseMip) +
                    "+" + std::to_string(b.mipCount) + ", layers " + std::to_string(b.baseLayer) + "+" +
                    std::to_string(b.layerCount));
    r.whole = r.baseMip == 0 && r.mipCount == d.mipLevels && r.baseLayer == 0 && r.layerCount == layers;
    return r;
}

uint64_t bufferBarrier(const BufferDesc& d, const BufferBarrier& b, const std::string& name) {
    accessesAllowed(d, b.before, name);
    accessesAllowed(d, b.after, name);
    const uint64_t size = b.size ? b.size : d.size - std::min(b.offset, d.size);
    if (b.offset >= d.size || size > d.size - b.offset)
        throw Error("barrier: range " + std::to_string(b.offset) + "+" + std::to_string(b.size) + " is outside " +
                    describeObject("buffer", name, std::to_string(d.size) + " bytes"));
    return size;
}

void mappable(const BufferDesc& d, const std::string& name) {
    if (d.access == MemoryAccess::GpuOnly)
        throw Error("map: " + describeObject("buffer", name, {}) +
                    " is GpuOnly; only Upload and Readback buffers can be mapped (use writeBuffer or a copy)");
}

void submittedLists(std::span<CommandList* const> lists) {
    for (size_t i = 0; i < lists.size(); ++i) {
        if (!lists[i]) throw Error("submit: list " + std::to_string(i) + " is null");
        for (size_t j = 0; j < i; ++j)
            if (lists[j] == lists[i])
                throw Error("submit: the same list at " + std::to_string(j) + " and " + std::to_string(i) +
                            " (a recording runs once)");
    }
}

void destroyedBeforeSubmit(const char* kind, uint32_t id) {
    throw Error(std::string("submit: the list uses ") + kind + " handle " + std::to_string(id) +
                ", destroyed after it was recorded; record the work again in a new command list (this one keeps "
                "its refused recording)");
}

}  // namespace fe::gdi::validate

namespace fe::gdi::validate {

PassSignature passSignature(const std::vector<AttachmentInfo>& colors, const AttachmentInfo* depth, Rect area) {
    PassSignature s;
    s.colorCount = uint32_t(std::min(colors.size(), s.colors.size()));
    for (uint32_t i = 0; i < s.colorCount; ++i) s.colors[i] = colors[i].format;
    if (depth) s.depth = depth->format;
    s.samples = colors.empty() ? (depth ? depth->samples : 1) : colors[0].samples;
    s.width = area.width;
    s.height = area.height;
    return s;
}

void secondaryNotEmpty() {
    throw Error("beginSecondary: the list must be empty (a secondary list records one pass's draws from its start)");
}
void onlyExecuteSecondary(const char* what) {
    throw Error(std::string(what) + " is not allowed in a render pass whose draws come from secondary lists "
                                    "(the primary list may only call executeSecondary and endRenderPass there)");
}
void notInSecondary(const char* what) { throw Error(std::string(what) + " is not allowed in a secondary list"); }
void submittedSecondary() {
    throw Error("submit: a secondary list is executed by a primary list (executeSecondary), not submitted");
}

namespace {
std::string signatureText(const PassSignature& s) {
    std::string t;
    for (uint32_t i = 0; i < s.colorCount; ++i) t += std::string(i ? ", " : "") + std::string(formatInfo(s.colors[i]).name);
    if (s.depth != Format::Undefined)
        t += std::string(t.empty() ? "" : ", ") + "depth " + std::string(formatInfo(s.depth).name);
    return t + "; " + std::to_string(s.samples) + " sample(s); " + std::to_string(s.width) + "x" + std::to_string(s.height);
}
}  // namespace

void executedSecondary(bool inSecondaryPass, bool isSecondary, bool ended, const PassSignature& list,
                       const PassSignature& pass, size_t index) {
    const std::string what = "executeSecondary: list " + std::to_string(index);
    if (!inSecondaryPass)
        throw Error("executeSecondary outside a render pass begun with secondaryLists (RenderPassDesc::secondaryLists)");
    if (!isSecondary) throw Error(what + " is not a secondary list (record it between beginSecondary and endSecondary)");
    if (!ended) throw Error(what + " is still recording (missing endSecondary)");
    if (!(list == pass))
        throw Error(what + " was begun for another pass (" + signatureText(list) + ") than the open one (" +
                    signatureText(pass) + ")");
}

}  // namespace fe::gdi::validate

namespace fe::gdi::validate {

std::vector<BindingSlot> pipelineBindings(const std::vector<BindingSlot>& declared,
                                          std::initializer_list<const ShaderInterface*> shaders, const std::string& pipeline,
                                          const DeviceLimits& limits) {
    const std::string what = "pipeline '" + pipeline + "'";
    std::vector<BindingSlot> used;  // by slot, stages merged
    for (const ShaderInterface* sh : shaders) {
        if (!sh) continue;
        for (const ShaderInterface::Binding& b : sh->bindings) {
            if (b.slot >= 64)
                fail(what, std::string("the ") + shaderStageName(sh->stage) + " shader uses binding " + std::to_string(b.slot) +
                               " ('" + b.name + "'); slots are 0 to 63");
            auto it = std::find_if(used.begin(), used.end(), [&](const BindingSlot& u) { return u.slot == b.slot; });
            if (it == used.end()) {
                used.push_back({b.slot, b.type, sh->stage});
            } else if (it->type != b.type) {
                fail(what, "slot " + std::to_string(b.slot) + " is a " + bindingTypeName(it->type) +
                               " in one shader and a " + bindingTypeName(b.type) + " ('" + b.name + "') in the " +
                               shaderStageName(sh->stage) + " shader");
            } else {
                it->stages = it->stages | sh->stage;
            }
        }
    }
    std::sort(used.begin(), used.end(), [](const BindingSlot& a, const BindingSlot& b) { return a.slot < b.slot; });
    const auto images = std::count_if(used.begin(), used.end(), [](const BindingSlot& u) { return u.type == BindingType::StorageTexture; });
    if (limits.maxStorageTextures && uint64_t(images) > limits.maxStorageTextures)
        fail(what, "the shaders use " + std::to_string(images) + " storage textures; this device binds at most " +
                       std::to_string(limits.maxStorageTextures) + " to one pipeline (limits.maxStorageTextures)");
    if (declared.empty()) return used;
    for (const BindingSlot& u : used) {
        auto it = std::find_if(declared.begin(), declared.end(), [&](const BindingSlot& d) { return d.slot == u.slot; });
        std::string user;
        for (const ShaderInterface* sh : shaders)
            if (sh && any(u.stages, sh->stage)) user += std::string(user.empty() ? "the " : " and ") + shaderStageName(sh->stage);
        if (it == declared.end())
            fail(what, "binding slot " + std::to_string(u.slot) + " (" + bindingTypeName(u.type) + ") is used by " + user +
                           " shader but missing from the pipeline's bindings (leave bindings empty to take them from the shaders)");
        if (it->type != u.type)
            fail(what, "binding slot " + std::to_string(u.slot) + " is declared a " + bindingTypeName(it->type) + ", but " + user +
                           " shader uses a " + bindingTypeName(u.type));
        if ((uint32_t(it->stages) & uint32_t(u.stages)) != uint32_t(u.stages))
            fail(what, "binding slot " + std::to_string(u.slot) + " is used by " + user +
                           " shader, which its declared stages leave out");
    }
    return declared;
}

namespace {
ScalarKind vertexKind(VertexFormat f) { return f == VertexFormat::UInt32 ? ScalarKind::Uint : ScalarKind::Float; }
}  // namespace

void vertexInputs(const GraphicsPipelineDesc& d, const ShaderInterface& vs, const std::string& pipeline) {
    const std::string what = "pipeline '" + pipeline + "'";
    for (const ShaderInterface::Variable& in : vs.inputs) {
        const VertexAttribute* found = nullptr;
        for (const VertexBufferLayout& vb : d.vertexBuffers)
            for (const VertexAttribute& a : vb.attributes)
                if (a.location == in.location) found = &a;
        if (!found)
            fail(what, "vertex shader input '" + in.name + "' (location " + std::to_string(in.location) +
                           ") has no attribute in the vertex layout");
        if (vertexKind(found->format) != in.kind)
            fail(what, "vertex shader input '" + in.name + "' (location " + std::to_string(in.location) + ") is " +
                           scalarKindName(in.kind) + ", its attribute's format gives " + scalarKindName(vertexKind(found->format)));
    }
}

void fragmentOutputs(const GraphicsPipelineDesc& d, const ShaderInterface& fs, const std::string& pipeline) {
    const std::string what = "pipeline '" + pipeline + "'";
    for (const ShaderInterface::Variable& out : fs.outputs) {
        if (out.location >= d.colorFormats.size()) continue;  // no target there: the value is dropped, as both APIs do
        const FormatInfo& f = formatInfo(d.colorFormats[out.location]);
        const ScalarKind want = f.isInteger ? ScalarKind::Uint : ScalarKind::Float;
        if (out.kind != want)
            fail(what, "fragment output '" + out.name + "' (location " + std::to_string(out.location) + ") is " +
                           scalarKindName(out.kind) + ", colour target " + std::to_string(out.location) + " is " +
                           std::string(f.name) + " (" + scalarKindName(want) + ")");
    }
}

void blendedTargets(const GraphicsPipelineDesc& d, const std::function<FormatCaps(Format)>& caps) {
    for (size_t i = 0; i < d.blend.size() && i < d.colorFormats.size(); ++i)
        if (d.blend[i].enable && !caps(d.colorFormats[i]).blend)
            fail(label("graphics pipeline", d.debugName),
                 "colour target " + std::to_string(i) + " (" + std::string(formatInfo(d.colorFormats[i]).name) +
                     ") is blended, which this device cannot do for that format (FormatCaps::blend)");
}

std::vector<BlendTargetState> writtenTargetBlends(const GraphicsPipelineDesc& d, const ShaderInterface* fs) {
    std::vector<BlendTargetState> blends(d.colorFormats.size());
    for (size_t i = 0; i < blends.size(); ++i) {
        if (i < d.blend.size()) blends[i] = d.blend[i];
        const bool written = fs && std::any_of(fs->outputs.begin(), fs->outputs.end(),
                                               [&](const ShaderInterface::Variable& o) { return i >= o.location && i < o.location + o.locations; });
        if (!written) blends[i].writeMask = ColorMask::None;
    }
    return blends;
}

void workgroup(const ShaderInterface& cs, const DeviceLimits& limits, const std::string& pipeline) {
    const uint64_t n = uint64_t(cs.workgroupSize[0]) * cs.workgroupSize[1] * cs.workgroupSize[2];
    if (limits.maxComputeWorkGroupInvocations && n > limits.maxComputeWorkGroupInvocations)
        fail("compute pipeline '" + pipeline + "'", "work group of " + std::to_string(n) + " invocations exceeds the device's " +
                                                        std::to_string(limits.maxComputeWorkGroupInvocations));
}

void querySetDesc(const QuerySetDesc& d, const DeviceFeatures& f) {
    const std::string what = std::string("query set '") + (d.debugName ? d.debugName : "") + "'";
    if (d.count == 0 || d.count > 4096) fail(what, "count " + std::to_string(d.count) + " is out of range (1..4096)");
    const bool supported = d.type == QueryType::Timestamp            ? f.timestamps
                           : d.type == QueryType::PipelineStatistics ? f.pipelineStatistics
                                                                     : f.occlusionQueries;
    if (!supported)
        fail(what, std::string(queryTypeName(d.type)) + " queries are not supported on this device (DeviceFeatures::" +
                       (d.type == QueryType::Timestamp ? "timestamps" : d.type == QueryType::PipelineStatistics ? "pipelineStatistics" : "occlusionQueries") + ")");
}

uint32_t queryValues(QueryType t) { return t == QueryType::PipelineStatistics ? 4 : 1; }

void queryDestination(const BufferDesc& d, const std::string& name, uint64_t offset, uint64_t bytes) {
    const std::string what = "resolveQueries into buffer '" + name + "'";
    if (!any(d.usage, BufferUsage::CopyDst)) fail(what, "the buffer has no CopyDst usage");
    if (offset % 8) fail(what, "offset " + std::to_string(offset) + " is not a multiple of 8");
    if (offset > d.size || bytes > d.size - offset)
        fail(what, std::to_string(bytes) + " bytes at offset " + std::to_string(offset) + " exceed its " +
                       std::to_string(d.size) + " bytes");
}

void queryRead(const QuerySetDesc& d, const std::string& name, uint32_t first, uint32_t count, size_t outSize) {
    const std::string what = "queryResults of set '" + name + "'";
    if (count == 0 || uint64_t(first) + count > d.count)
        fail(what, "queries " + std::to_string(first) + ".." + std::to_string(uint64_t(first) + count) +
                       " are out of range (the set has " + std::to_string(d.count) + ")");
    if (outSize < uint64_t(count) * queryValues(d.type))
        fail(what, "room for " + std::to_string(outSize) + " values; " + std::to_string(uint64_t(count) * queryValues(d.type)) +
                       " needed");
}

namespace {
std::string queryName(const std::string& set, uint32_t index) {
    return "query " + std::to_string(index) + " of set '" + set + "'";
}
void queryIndex(const QuerySetDesc& d, const std::string& name, uint32_t index, const char* what) {
    if (index >= d.count)
        fail(what, queryName(name, index) + " is out of range (the set has " + std::to_string(d.count) + ")");
}
}  // namespace

void QueryRecording::written(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t index, const char* what) {
    queryIndex(d, name, index, what);
    for (const Use& u : used_)
        if (u.set == set && u.index == index)
            fail(what, queryName(name, index) + " is already written in this recording (each query once per submission)");
}

void QueryRecording::begin(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t index, bool inPass) {
    if (d.type == QueryType::Timestamp) fail("beginQuery", "set '" + name + "' holds timestamps: use writeTimestamp");
    if (d.type != QueryType::PipelineStatistics && !inPass)
        fail("beginQuery", std::string(queryTypeName(d.type)) + " queries begin and end inside a render pass");
    written(d, name, set, index, "beginQuery");
    auto& active = active_[size_t(d.type)];
    if (active) fail("beginQuery", std::string("a ") + queryTypeName(d.type) + " query is already active (" +
                                       std::to_string(active->index) + "): end it first");
    active = Active{set, index, inPass};
    used_.push_back({set, index, false});
}

void QueryRecording::end(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t index, bool inPass) {
    queryIndex(d, name, index, "endQuery");
    auto& active = d.type == QueryType::Timestamp ? active_[0] : active_[size_t(d.type)];
    if (d.type == QueryType::Timestamp || !active || active->set != set || active->index != index)
        fail("endQuery", queryName(name, index) + " is not active");
    if (active->inPass != inPass)
        fail("endQuery", queryName(name, index) + (active->inPass ? " began inside the render pass and must end in it"
                                                                   : " began outside a render pass and must end outside"));
    active.reset();
    for (Use& u : used_)
        if (u.set == set && u.index == index) u.ended = true;
}

void QueryRecording::timestamp(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t index, bool inPass) {
    if (d.type != QueryType::Timestamp) fail("writeTimestamp", "set '" + name + "' is not a Timestamp set");
    if (inPass) fail("writeTimestamp", "inside a render pass (timestamps are written between passes)");
    written(d, name, set, index, "writeTimestamp");
    used_.push_back({set, index, true});
}

void QueryRecording::resolve(const QuerySetDesc& d, const std::string& name, uint32_t set, uint32_t first, uint32_t count) const {
    if (count == 0 || uint64_t(first) + count > d.count)
        fail("resolveQueries", "queries " + std::to_string(first) + ".." + std::to_string(uint64_t(first) + count) +
                                   " of set '" + name + "' are out of range (the set has " + std::to_string(d.count) + ")");
    for (uint32_t i = first; i < first + count; ++i) {
        auto it = std::find_if(used_.begin(), used_.end(), [&](const Use& u) { return u.set == set && u.index == i; });
        if (it == used_.end() || !it->ended)
            fail("resolveQueries", queryName(name, i) + " has not been written (and ended) earlier in this recording");
    }
}

void QueryRecording::endPass() const {
    for (const auto& a : active_)
        if (a && a->inPass) fail("endRenderPass", "query " + std::to_string(a->index) + " begun in the pass is still active");
}

void QueryRecording::finish() const {
    for (const auto& a : active_)
        if (a) fail("submit", "query " + std::to_string(a->index) + " is still active: end it before submitting");
    for (const auto& [timer, ended] : timers_)
        if (!ended) fail("submit", "a timer begun in this recording was not ended (endTimer)");
}

// A timer holds one span per submission: begun twice it would measure from the second begin on
// one backend and be a validation error on another; ended unbegun, GL read a negative time.
void QueryRecording::beginTimer(uint32_t timer) {
    for (const auto& t : timers_)
        if (t.first == timer) fail("beginTimer", "the timer was already begun in this recording (one span per submission)");
    timers_.push_back({timer, false});
}

void QueryRecording::endTimer(uint32_t timer) {
    for (auto& t : timers_)
        if (t.first == timer) {
            if (t.second) fail("endTimer", "the timer was already ended in this recording");
            t.second = true;
            return;
        }
    fail("endTimer", "the timer was not begun in this recording (beginTimer first)");
}

void queriesOncePerSubmission(std::span<const QueryRecording* const> lists) {
    for (size_t i = 0; i < lists.size(); ++i)
        for (const QueryRecording::Use& u : lists[i]->used())
            for (size_t j = 0; j < i; ++j)
                for (const QueryRecording::Use& v : lists[j]->used())
                    if (u.set == v.set && u.index == v.index)
                        fail("submit", "query " + std::to_string(u.index) + " of one set is written by two lists of this "
                                       "submission (each query once per submission)");
}

uint32_t pipelineConstants(std::initializer_list<const ShaderInterface*> shaders, const std::string& pipeline) {
    uint32_t bytes = 0;
    for (const ShaderInterface* sh : shaders) {
        if (!sh) continue;
        if (sh->pushConstantBytes > kMaxConstantBytes)
            fail("pipeline '" + pipeline + "'", std::string("the ") + shaderStageName(sh->stage) + " shader's constants block is " +
                                                    std::to_string(sh->pushConstantBytes) + " bytes; at most " +
                                                    std::to_string(kMaxConstantBytes) + " (kMaxConstantBytes)");
        bytes = std::max(bytes, sh->pushConstantBytes);
    }
    return bytes;
}

void badConstantsRange(uint32_t offset, size_t size) {
    fail("setConstants", "offset " + std::to_string(offset) + " and size " + std::to_string(size) +
                             " must be multiples of 4, the size not 0, and offset + size at most " +
                             std::to_string(kMaxConstantBytes) + " (kMaxConstantBytes)");
}

void specialization(const std::vector<SpecializationConstant>& values,
                    std::initializer_list<const ShaderInterface*> shaders, const std::string& pipeline) {
    const std::string what = "pipeline '" + pipeline + "'";
    for (size_t i = 0; i < values.size(); ++i) {
        const SpecializationConstant& v = values[i];
        for (size_t j = 0; j < i; ++j)
            if (values[j].id == v.id) fail(what, "specialization constant " + std::to_string(v.id) + " is given twice");
        const ShaderInterface::SpecConstant* declared = nullptr;
        for (const ShaderInterface* sh : shaders) {
            if (!sh) continue;
            for (const ShaderInterface::SpecConstant& c : sh->specConstants)
                if (c.id == v.id) {
                    if (declared && (declared->isBool != c.isBool || declared->kind != c.kind))
                        fail(what, "specialization constant " + std::to_string(v.id) + " has a different type in the " +
                                       shaderStageName(sh->stage) + " shader");
                    declared = &c;
                }
        }
        if (!declared)
            fail(what, "specialization constant " + std::to_string(v.id) +
                           " is not declared by its shaders (layout(constant_id = " + std::to_string(v.id) + "))");
        if (declared->isBool && v.bits > 1)
            fail(what, "specialization constant " + std::to_string(v.id) + " ('" + declared->name +
                           "') is a bool: its value is 0 or 1, not " + std::to_string(v.bits));
        if (!declared->isBool && declared->kind == ScalarKind::Other)
            fail(what, "specialization constant " + std::to_string(v.id) + " ('" + declared->name +
                           "') is not a 32-bit bool, int, uint or float");
    }
}

PassSignature pipelineSignature(const GraphicsPipelineDesc& d) {
    PassSignature s;
    s.colorCount = uint32_t(std::min(d.colorFormats.size(), s.colors.size()));
    for (uint32_t i = 0; i < s.colorCount; ++i) s.colors[i] = d.colorFormats[i];
    s.depth = d.depthFormat;
    s.samples = d.multisample.sampleCount;
    return s;
}

void pipelineFitsPass(const PassSignature& p, const PassSignature& pass, const char* pipelineName) {
    if (p.samples != pass.samples) pipelineSamples(p.samples, pass.samples, pipelineName);
    auto formats = [](const PassSignature& s) {
        std::string t = "colour [";
        for (uint32_t i = 0; i < s.colorCount; ++i) t += std::string(i ? ", " : "") + std::string(formatInfo(s.colors[i]).name);
        return t + "], depth " + (s.depth == Format::Undefined ? std::string("none") : std::string(formatInfo(s.depth).name));
    };
    bool same = p.colorCount == pass.colorCount && p.depth == pass.depth;
    for (uint32_t i = 0; same && i < p.colorCount; ++i) same = p.colors[i] == pass.colors[i];
    if (!same)
        fail(label("setPipeline: pipeline", pipelineName),
             "renders to " + formats(p) + " but the render pass has " + formats(pass));
}

}  // namespace fe::gdi::validate

namespace fe::gdi::validate {

BindingLimits uniformBindingLimits(const DeviceLimits& l) {
    return {l.uniformBufferOffsetAlignment ? l.uniformBufferOffsetAlignment - 1u : 0u,
            l.maxUniformBufferRange ? l.maxUniformBufferRange : ~uint64_t(0), "uniformBufferOffsetAlignment",
            "maxUniformBufferRange"};
}
BindingLimits storageBindingLimits(const DeviceLimits& l) {
    return {l.storageBufferOffsetAlignment ? l.storageBufferOffsetAlignment - 1u : 0u,
            l.maxStorageBufferRange ? l.maxStorageBufferRange : ~uint64_t(0), "storageBufferOffsetAlignment",
            "maxStorageBufferRange"};
}

void bindingLimits(uint64_t offset, uint64_t size, const BindingLimits& limits, const char* what) {
    if (offset & limits.alignMask)
        throw Error(std::string(what) + ": offset " + std::to_string(offset) + " is not a multiple of the device's " +
                    limits.alignmentName + " (" + std::to_string(limits.alignMask + 1) + ")");
    if (size > limits.maxRange)
        throw Error(std::string(what) + ": " + std::to_string(size) + " bytes exceed the device's " + limits.rangeName + " (" +
                    std::to_string(limits.maxRange) + ")");
}

}  // namespace fe::gdi::validate

namespace fe::gdi::validate {

void depthBias(float constant, float slope, float clamp, const DeviceFeatures& features) {
    if (!std::isfinite(constant) || !std::isfinite(slope) || !std::isfinite(clamp))
        throw Error("setDepthBias: values must be finite");
    if (clamp != 0 && !features.depthBiasClamp) throw Error("setDepthBias: depth bias clamp is not supported on this device");
}

}  // namespace fe::gdi::validate

namespace fe::gdi::validate {

void notFilterable(const std::string& texture, Format format, const std::string& sampler) {
    throw Error("setTexture: " + label("sampler", sampler.c_str()) + " filters linearly, but " +
                label("texture", texture.c_str()) + " (" + std::string(formatInfo(format).name) +
                ") cannot be filtered linearly on this device (FormatCaps::linearFilter); use Nearest filters, or a "
                "comparison sampler for depth");
}

}  // namespace fe::gdi::validate

namespace fe::gdi::validate {

void bufferUsage(const BufferDesc& d, BufferUsage usage, const std::string& name, const char* what) {
    if (any(d.usage, usage)) return;
    throw Error(std::string(what) + ": " + label("buffer", name.c_str()) + " lacks " + bufferUsageNames(usage, " or ") +
                " usage (it was created with " + bufferUsageNames(d.usage) + ")");
}

void textureUsage(const TextureDesc& d, TextureUsage usage, const std::string& name, const char* what) {
    if (any(d.usage, usage)) return;
    throw Error(std::string(what) + ": " + label("texture", name.c_str()) + " lacks " + textureUsageNames(usage, " or ") +
                " usage (it was created with " + textureUsageNames(d.usage) + ")");
}

void destroyedHandle(const char* kind, uint32_t id) {
    throw Error(std::string("destroy: ") + kind + " handle " + std::to_string(id) +
                " is not live (destroyed already, or made by another device)");
}

void stateOutsidePass(const char* what) {
    throw Error(std::string(what) + " outside a render pass (each pass starts from its pipeline's state: set it "
                "after beginRenderPass and setPipeline)");
}

}  // namespace fe::gdi::validate

namespace fe::gdi::validate {

uint64_t clearRange(const BufferDesc& d, const std::string& name, uint64_t offset, uint64_t size) {
    bufferUsage(d, BufferUsage::CopyDst | BufferUsage::Storage, name, "clearBuffer");  // a transfer or a UAV clear
    const uint64_t bytes = size == 0 && offset <= d.size ? d.size - offset : size;
    if (offset % 4 || bytes % 4)
        throw Error("clearBuffer: " + label("buffer", name.c_str()) + ": offset " + std::to_string(offset) + " and size " +
                    std::to_string(bytes) + " must be multiples of 4");
    bufferRange(d, offset, bytes, "clearBuffer");
    return bytes;
}

}  // namespace fe::gdi::validate

namespace fe::gdi::validate {

TextureSpan bindingSpan(uint32_t id, uint32_t viewOf, uint32_t baseMip, uint32_t baseLayer, const TextureDesc& view,
                        std::optional<uint32_t> oneMip) {
    TextureSpan s{.texture = viewOf ? viewOf : id, .baseMip = baseMip, .mipCount = view.mipLevels, .baseLayer = baseLayer,
                  .layerCount = view.depthOrLayers};
    if (view.dimension == TextureDimension::Texture3D) s.baseLayer = 0, s.layerCount = UINT32_MAX;  // every slice
    if (oneMip) s.baseMip += *oneMip, s.mipCount = 1;
    return s;
}

void PassAttachments::add(const TextureSpan& whole, uint32_t mip, uint32_t layer, uint8_t role, const char* passName) {
    if (count_ == 0) passName_ = passName ? passName : "";
    const TextureSpan a{.texture = whole.texture, .baseMip = whole.baseMip + mip, .mipCount = 1,
                        .baseLayer = whole.baseLayer + layer, .layerCount = 1};
    for (uint32_t i = 0; i < count_; ++i) {
        if (!reaches(a, at_[i])) continue;
        const std::string why = roleName(roles_[i]) + " and " + roleName(role) + " are the same subresource (" +
                                label("texture", names_[i].c_str()) + ", mip " + std::to_string(a.baseMip) + ", layer " +
                                std::to_string(a.baseLayer) + "): each attachment needs its own";
        count_ = 0;  // the pass does not begin: nothing may be checked against its half-read attachments
        fail(label("render pass", passName), why);
    }
    at_[count_] = a;
    kinds_[count_] = role == kDepthRole ? kDepth : kColour;
    roles_[count_] = role;
    names_[count_].assign(whole.name);
    ++count_;
}

std::string PassAttachments::roleName(uint8_t role) {
    if (role < 8) return "colour attachment " + std::to_string(role);
    if (role < 16) return "colour attachment " + std::to_string(role - 8) + "'s resolve target";
    return role == kDepthRole ? "the depth attachment" : "the depth resolve target";
}

void PassAttachments::failed(uint32_t slot, const TextureSpan& s, bool storage, const char* pipelineName) const {
    uint32_t i = 0;
    while (i + 1 < count_ && !reaches(s, at_[i])) ++i;
    const std::string how = storage ? " stores to " : " samples ";
    fail(label("draw with pipeline", pipelineName),
         "slot " + std::to_string(slot) + how + label("texture", names_[i].c_str()) + " (mip " + std::to_string(at_[i].baseMip) +
             ", layer " + std::to_string(at_[i].baseLayer) + "), which " + roleName(roles_[i]) + " of " +
             label("render pass", passName_.c_str()) + " writes: a feedback loop, undefined on every API. Read another mip or layer, or a copy" +
             (roles_[i] == kDepthRole ? " (a pipeline that writes neither depth nor stencil may sample the depth attachment)"
                                      : ""));
}

void FeedbackLoops::check(uint32_t slot, bool pipelineWritesDepthStencil, const char* pipelineName) const {
    if (refused(slot, pipelineWritesDepthStencil)) pass_.failed(slot, slots_[slot], storage_ & bit(slot), pipelineName);
}

bool writesDepthStencil(const GraphicsPipelineDesc& d) {
    const DepthStencilState& ds = d.depthStencil;
    auto writes = [](const StencilFaceState& f) {
        return f.failOp != StencilOp::Keep || f.depthFailOp != StencilOp::Keep || f.passOp != StencilOp::Keep;
    };
    return ds.depthWrite || (ds.stencilTest && ds.stencilWriteMask && (writes(ds.front) || writes(ds.back)));
}

}  // namespace fe::gdi::validate
