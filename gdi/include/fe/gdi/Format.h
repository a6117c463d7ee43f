// Layer 1 (Primitives): pixel and vertex formats, shared by every backend.
#pragma once
#include <cstdint>
#include <string_view>

namespace fe::gdi {

enum class Format : uint8_t {
    Undefined,
    RGBA8,       // unorm
    RGBA8_SRGB,  // unorm, sRGB-encoded: decoded on sample, encoded on write
    RGBA16F,
    RG16F,
    R16F,
    RGBA32F,
    RG32F,
    R32F,
    R32U,
    R11G11B10F,  // packed unsigned float, no alpha
    D32F,
    D24S8,  // read back as 32-bit texels: depth in the low 24 bits, stencil in the high 8
    D16,    // unorm
    D32F_S8,  // read back as 64-bit texels: float depth, then a 32-bit word with stencil in its low 8 bits
    S8,  // stencil only (FormatCaps say where it can be an attachment); one byte per texel
    // Block-compressed (4x4 texel blocks), sampled only; DeviceFeatures::textureCompressionBC.
    BC1,  // RGB 5:6:5 endpoints + 1-bit alpha, 8 bytes per block
    BC1_SRGB,
    BC3,  // BC1 colour + interpolated alpha, 16 bytes
    BC3_SRGB,
    BC4,  // one channel (R), 8 bytes
    BC5,  // two channels (RG), 16 bytes
    BC7,  // RGBA, eight block modes, 16 bytes
    BC7_SRGB,
    // Bytes in the order blue, green, red, alpha (the common swap-chain and interop layout);
    // shaders see RGBA as for RGBA8. Copied only to and from BGRA8 formats (GL stores them RGBA),
    // never storage images (SPIR-V has no such image format). Views between them and RGBA8 /
    // RGBA8_SRGB read red and blue swapped, sampled only (channelOrdersDiffer).
    BGRA8,
    BGRA8_SRGB,
    Count
};

struct FormatInfo {
    std::string_view name;
    uint32_t bytesPerPixel = 0;
    uint32_t channels = 0;  // colour channels stored (0 for depth)
    bool isFloat = false;
    bool isSrgb = false;
    bool isInteger = false;
    bool hasDepth = false;
    bool hasStencil = false;
    uint32_t blockSize = 1;      // texels per block edge: 4 for block-compressed formats
    uint32_t bytesPerBlock = 0;  // compressed formats (bytesPerPixel is 0 for them)
};

const FormatInfo& formatInfo(Format f);
// A format of the depth/stencil attachment: depth, stencil or both (S8 has no depth).
inline bool isDepthFormat(Format f) { return formatInfo(f).hasDepth || formatInfo(f).hasStencil; }
// Storage-image formats beyond SPIR-V's base set: a shader declaring one needs the capability
// StorageImageExtendedFormats (DeviceFeatures::storageImageExtendedFormats).
inline bool isExtendedStorageFormat(Format f) {
    return f == Format::RG16F || f == Format::R16F || f == Format::RG32F || f == Format::R11G11B10F;
}
inline bool isCompressedFormat(Format f) { return formatInfo(f).blockSize > 1; }
// Depth and stencil in one texture (D24S8, D32F_S8): buffer copies take one aspect at a time.
inline bool hasTwoAspects(Format f) { return formatInfo(f).hasDepth && formatInfo(f).hasStencil; }

// Which part of a depth/stencil texel a buffer copy moves (TextureRegion::aspect). All: the
// whole texel of a colour format, or the one aspect of D16, D32F and S8.
enum class TextureAspect : uint8_t { All, Depth, Stencil };
// Bytes of one texel of `aspect` in a buffer (Vulkan's buffer layouts, the same on GL): D16's
// depth 2 (unorm), D32F's and D32F_S8's 4 (float), D24S8's 4 (depth in the low 24 bits, the high
// 8 undefined after a copy from the texture and ignored by one into it), any stencil 1; colour
// formats their bytesPerPixel. 0 when the format has no such aspect (or two, for All).
uint32_t aspectTexelBytes(Format f, TextureAspect aspect);
// Bytes of a tightly packed width x height image (compressed: whole 4x4 blocks).
uint64_t imageByteSize(Format f, uint32_t width, uint32_t height);
// The sRGB form of a UNORM format or the UNORM form of an sRGB one (RGBA8, BC1, BC3, BC7);
// Undefined for the others.
Format srgbPair(Format f);
// Whether texels of `a` may be read as `b` (copies between textures, texture views): the same
// format, its sRGB/UNORM pair, or two uncompressed colour formats of the same texel size.
bool formatsCompatible(Format a, Format b);
// Whether one of `a` and `b` is RGBA8 or RGBA8_SRGB and the other BGRA8 or BGRA8_SRGB: a view
// between them reads the texels' red and blue swapped, and is sampled only (GL stores both orders
// as RGBA and swaps the view's channels by its swizzle, which writes do not go through).
bool channelOrdersDiffer(Format a, Format b);
// Whether a texture of format `a` may have a view of format `b` (TextureDesc::viewFormats):
// formatsCompatible, or the other channel order of the 8-bit RGBA formats (channelOrdersDiffer).
bool viewFormatsCompatible(Format a, Format b);
// Parses the names printed by formatInfo (case-sensitive); Undefined when unknown.
Format formatFromName(std::string_view name);

enum class VertexFormat : uint8_t {
    Float,
    Float2,
    Float3,
    Float4,
    Half2,
    Half4,
    UNorm8x4,
    SNorm8x4,
    UNorm16x2,
    SNorm16x2,
    UInt32,  // integer attribute (uint in the shader)
    Count
};

struct VertexFormatInfo {
    std::string_view name;
    uint32_t bytes = 0;
    uint32_t components = 0;
};
const VertexFormatInfo& vertexFormatInfo(VertexFormat f);

}  // namespace fe::gdi
