// Shared validation: Copies between buffers and textures: regions, texel layouts, overlap and the usages each needs.
#include "ValidationSupport.h"

namespace fe::gdi::validate {

// The aspect a region names exists in the format, and is one aspect (aspectTexelBytes' rule).
static void aspect(Format f, TextureAspect a, const std::string& w) {
    if (uint8_t(a) > uint8_t(TextureAspect::Stencil))
        fail(w, "aspect " + std::to_string(unsigned(a)) + " is not a TextureAspect");
    if (aspectTexelBytes(f, a) != 0) return;
    const std::string format(formatInfo(f).name);
    if (a == TextureAspect::All)
        fail(w, format + " has depth and stencil: a region names one (TextureRegion::aspect " +
                    "Depth or Stencil)");
    fail(w, format + " has no " + (a == TextureAspect::Depth ? "depth" : "stencil") + " aspect");
}

TextureRegion textureRegion(const TextureDesc& d, const TextureRegion& r, const std::string& name,
                            const char* what, bool perSample) {
    const std::string w = std::string(what) + ": " + label("texture", name.c_str());
    if (d.sampleCount > 1 && !perSample)
        fail(w,
             "multisampled textures go to and from buffers only through a single-sample one "
             "(resolve them, or read samples with sampler2DMS)");
    aspect(d.format, r.aspect, w);
    transientContents(d, w);
    if (r.mipLevel >= d.mipLevels)
        fail(w, "mip level " + std::to_string(r.mipLevel) + " out of range (" +
                    std::to_string(d.mipLevels) + " levels)");
    const Extent3 e = mipExtent(d, r.mipLevel);
    TextureRegion out = r;
    out.width = r.width ? r.width : (r.x < e.width ? e.width - r.x : 0);
    out.height = r.height ? r.height : (r.y < e.height ? e.height - r.y : 0);
    out.depth = r.depth ? r.depth : (r.z < e.depthOrLayers ? e.depthOrLayers - r.z : 0);
    auto beyond = [](uint32_t at, uint32_t n, uint32_t size) {
        return n == 0 || at >= size || n > size - at;
    };
    if (beyond(r.x, out.width, e.width) || beyond(r.y, out.height, e.height) ||
        beyond(r.z, out.depth, e.depthOrLayers))
        fail(w, "region at (" + std::to_string(r.x) + ", " + std::to_string(r.y) + ", " +
                    std::to_string(r.z) + ") of " + std::to_string(out.width) + "x" +
                    std::to_string(out.height) + "x" + std::to_string(out.depth) +
                    " is outside mip level " + std::to_string(r.mipLevel) + " (" +
                    std::to_string(e.width) + "x" + std::to_string(e.height) + "x" +
                    std::to_string(e.depthOrLayers) + ")");
    const uint32_t block = formatInfo(d.format).blockSize;
    auto aligned = [&](uint32_t at, uint32_t n, uint32_t size) {
        return at % block == 0 && (n % block == 0 || at + n == size);
    };
    if (block > 1 && !(aligned(r.x, out.width, e.width) && aligned(r.y, out.height, e.height)))
        fail(
            w,
            "a compressed region starts on a 4x4 block and spans whole blocks (or reaches the edge)");
    return out;
}

ResolvedLayout texelLayout(Format f, const TextureRegion& region, const TexelLayout& l,
                           const char* what) {
    const FormatInfo& fi = formatInfo(f);
    const bool compressed = fi.blockSize > 1;
    const uint32_t unit =
        compressed ? fi.bytesPerBlock : aspectTexelBytes(f, region.aspect);  // texel or block
    const uint32_t columns = (region.width + fi.blockSize - 1) / fi.blockSize;
    const uint32_t rows = (region.height + fi.blockSize - 1) / fi.blockSize;
    const uint64_t rowBytes = uint64_t(columns) * unit;
    ResolvedLayout r{l};
    r.layout.bytesPerRow = l.bytesPerRow ? l.bytesPerRow : uint32_t(rowBytes);
    r.layout.rowsPerImage = l.rowsPerImage ? l.rowsPerImage : rows;
    const std::string w = what;
    if (l.offset % 4 || l.offset % unit)
        fail(w, "offset " + std::to_string(l.offset) +
                    " is not a multiple of 4 and of the texel size (" + std::to_string(unit) + ")");
    if (r.layout.bytesPerRow % unit || r.layout.bytesPerRow < rowBytes)
        fail(w, "bytesPerRow " + std::to_string(r.layout.bytesPerRow) +
                    " is not a multiple of the texel size (" + std::to_string(unit) +
                    ") of at least one row (" + std::to_string(rowBytes) + ")");
    if (r.layout.rowsPerImage < rows)
        fail(w, "rowsPerImage " + std::to_string(r.layout.rowsPerImage) +
                    " is less than the region's " + std::to_string(rows) + " rows");
    if (compressed && (r.layout.bytesPerRow != rowBytes || r.layout.rowsPerImage != rows))
        fail(w, "compressed texels are packed tightly (bytesPerRow and rowsPerImage 0)");
    r.end =
        l.offset +
        (uint64_t(region.depth - 1) * r.layout.rowsPerImage + (rows - 1)) * r.layout.bytesPerRow +
        rowBytes;
    return r;
}

// The usages a buffer <-> texture copy needs, by direction.
static void bufferTextureUsages(const TextureDesc& t, const std::string& textureName,
                                const BufferDesc& b, const std::string& bufferName, bool toTexture,
                                const char* what) {
    textureUsage(t, toTexture ? TextureUsage::CopyDst : TextureUsage::CopySrc, textureName, what);
    bufferUsage(b, toTexture ? BufferUsage::CopySrc : BufferUsage::CopyDst, bufferName, what);
}

RegionCopy bufferTextureRegion(const TextureDesc& t, const std::string& name, const BufferDesc& b,
                               const std::string& bufferName, const TextureRegion& region,
                               const TexelLayout& layout, bool toTexture, const char* what) {
    bufferTextureUsages(t, name, b, bufferName, toTexture, what);
    const TextureRegion r = textureRegion(t, region, name, what);
    const ResolvedLayout l = texelLayout(t.format, r, layout, what);
    bufferRange(b, l.layout.offset, l.end - l.layout.offset, what);
    return {r, l.layout};
}

void dataSpan(size_t size, uint64_t end, const char* what) {
    if (size < end)
        fail(what, std::to_string(size) + " bytes of data; the region and layout span " +
                       std::to_string(end));
}

std::pair<TextureRegion, TextureRegion> textureCopy(const TextureDesc& dst,
                                                    const std::string& dstName, TextureRegion dstAt,
                                                    bool sameTexture, const TextureDesc& src,
                                                    const std::string& srcName,
                                                    const TextureRegion& srcRegion) {
    textureUsage(src, TextureUsage::CopySrc, srcName, "copyTexture source");
    textureUsage(dst, TextureUsage::CopyDst, dstName, "copyTexture destination");
    if (isDepthFormat(src.format) || isDepthFormat(dst.format))
        fail("copyTexture",
             "regions of depth/stencil textures are copied through a buffer (one "
             "aspect each) or whole (copyTexture(dst, src, mip))");
    if (src.sampleCount != dst.sampleCount)
        fail("copyTexture", "'" + srcName + "' has " + std::to_string(src.sampleCount) +
                                " sample(s) and '" + dstName + "' " +
                                std::to_string(dst.sampleCount) + ": copies keep every sample");
    const TextureRegion s = textureRegion(src, srcRegion, srcName, "copyTexture source", true);
    if (!formatsCompatible(src.format, dst.format))
        fail("copyTexture", std::string(formatInfo(src.format).name) +
                                " texels cannot be copied into " +
                                std::string(formatInfo(dst.format).name) +
                                " (the same format, its sRGB/UNORM pair, or the same texel size)");
    if ((src.dimension == TextureDimension::Texture3D) !=
        (dst.dimension == TextureDimension::Texture3D))
        fail("copyTexture", "between a 3D texture and a layered one");
    dstAt.width = s.width, dstAt.height = s.height, dstAt.depth = s.depth;
    const TextureRegion d = textureRegion(dst, dstAt, dstName, "copyTexture destination", true);
    auto apart = [](uint32_t a, uint32_t b, uint32_t n) { return a + n <= b || b + n <= a; };
    if (sameTexture && s.mipLevel == d.mipLevel &&
        !(apart(s.x, d.x, s.width) || apart(s.y, d.y, s.height) || apart(s.z, d.z, s.depth)))
        fail("copyTexture", "source and destination overlap in '" + srcName + "'");
    return {d, s};
}

std::pair<TextureRegion, TextureRegion> textureResolve(const TextureDesc& dst,
                                                       const std::string& dstName,
                                                       TextureRegion dstAt, const TextureDesc& src,
                                                       const std::string& srcName,
                                                       const TextureRegion& srcRegion) {
    textureUsage(src, TextureUsage::CopySrc, srcName, "resolveTexture source");
    textureUsage(dst, TextureUsage::CopyDst, dstName, "resolveTexture destination");
    if (src.sampleCount == 1 || dst.sampleCount != 1)
        fail("resolveTexture", "resolves a multisampled texture ('" + srcName +
                                   "': " + std::to_string(src.sampleCount) +
                                   " sample(s)) into a single-sample one ('" + dstName +
                                   "': " + std::to_string(dst.sampleCount) + ")");
    const FormatInfo& f = formatInfo(src.format);
    if (src.format != dst.format || isDepthFormat(src.format) || f.isInteger)
        fail("resolveTexture",
             "both textures have one colour format that averages (not integer "
             "or depth: resolve those in a render pass); got " +
                 std::string(f.name) + " and " + std::string(formatInfo(dst.format).name));
    const TextureRegion s = textureRegion(src, srcRegion, srcName, "resolveTexture source", true);
    dstAt.width = s.width, dstAt.height = s.height, dstAt.depth = s.depth;
    return {textureRegion(dst, dstAt, dstName, "resolveTexture destination"), s};
}

void wholeTextureCopy(const TextureDesc& dst, const std::string& dstName, const TextureDesc& src,
                      const std::string& srcName, uint32_t mip) {
    textureUsage(src, TextureUsage::CopySrc, srcName, "copyTexture source");
    textureUsage(dst, TextureUsage::CopyDst, dstName, "copyTexture destination");
    if (dst.format != src.format || dst.width != src.width || dst.height != src.height ||
        dst.dimension != src.dimension || dst.depthOrLayers != src.depthOrLayers ||
        dst.sampleCount != src.sampleCount)
        fail("copyTexture",
             "'" + srcName + "' and '" + dstName + "' differ in format, kind, size or samples");
    if (mip >= dst.mipLevels || mip >= src.mipLevels) fail("copyTexture", "mip level out of range");
}

void subresourceBufferCopy(const TextureDesc& t, const std::string& textureName, Subresource at,
                           const BufferDesc& b, const std::string& bufferName, uint64_t offset,
                           bool toTexture, const char* what) {
    bufferTextureUsages(t, textureName, b, bufferName, toTexture, what);
    subresource(t, at, what, textureName);
    if (hasTwoAspects(t.format))
        fail(what, std::string(formatInfo(t.format).name) +
                       " has depth and stencil: copy each with a TextureRegion naming its aspect");
    if (t.sampleCount > 1)
        fail(what,
             "multisampled textures go to and from buffers only through a single-sample one "
             "(resolve them, or read samples with sampler2DMS)");
    const Extent3 e = mipExtent(t, at.mipLevel);
    bufferRange(b, offset, imageByteSize(t.format, e.width, e.height), what);
    if (offset % 4) fail(what, "buffer offset must be a multiple of 4");
}

void bufferCopy(const BufferDesc& dst, const std::string& dstName, uint64_t dstOffset,
                const BufferDesc& src, const std::string& srcName, uint64_t srcOffset,
                uint64_t size, bool sameBuffer) {
    bufferUsage(src, BufferUsage::CopySrc, srcName, "copyBuffer source");
    bufferUsage(dst, BufferUsage::CopyDst, dstName, "copyBuffer destination");
    bufferRange(dst, dstOffset, size, "copyBuffer destination");
    bufferRange(src, srcOffset, size, "copyBuffer source");
    if (sameBuffer && size && dstOffset < srcOffset + size && srcOffset < dstOffset + size)
        fail(label("buffer", dstName.c_str()),
             "copyBuffer: the source [" + std::to_string(srcOffset) + ", " +
                 std::to_string(srcOffset + size) + ") and destination [" +
                 std::to_string(dstOffset) + ", " + std::to_string(dstOffset + size) + ") overlap");
}

uint64_t clearRange(const BufferDesc& d, const std::string& name, uint64_t offset, uint64_t size) {
    bufferUsage(d, BufferUsage::CopyDst | BufferUsage::Storage, name,
                "clearBuffer");  // a transfer or a UAV clear
    const uint64_t bytes = size == 0 && offset <= d.size ? d.size - offset : size;
    if (offset % 4 || bytes % 4)
        throw Error("clearBuffer: " + label("buffer", name.c_str()) + ": offset " +
                    std::to_string(offset) + " and size " + std::to_string(bytes) +
                    " must be multiples of 4");
    bufferRange(d, offset, bytes, "clearBuffer");
    return bytes;
}

}  // namespace fe::gdi::validate
