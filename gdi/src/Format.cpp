#include "fe/gdi/Format.h"

namespace fe::gdi {

namespace {
// Indexed by Format; order must follow the enum.
const FormatInfo kFormats[] = {
    {"Undefined", 0, 0},
    {"RGBA8", 4, 4},
    {"RGBA8_SRGB", 4, 4, false, true},
    {"RGBA16F", 8, 4, true},
    {"RG16F", 4, 2, true},
    {"R16F", 2, 1, true},
    {"RGBA32F", 16, 4, true},
    {"RG32F", 8, 2, true},
    {"R32F", 4, 1, true},
    {"R32U", 4, 1, false, false, true},
    {"R11G11B10F", 4, 3, true},
    {"D32F", 4, 0, true, false, false, true, false},
    {"D24S8", 4, 0, false, false, false, true, true},
    {"D16", 2, 0, false, false, false, true, false},
    {"D32F_S8", 8, 0, true, false, false, true, true},
    {"S8", 1, 0, false, false, true, false, true},
    {"BC1", 0, 4, false, false, false, false, false, 4, 8},
    {"BC1_SRGB", 0, 4, false, true, false, false, false, 4, 8},
    {"BC3", 0, 4, false, false, false, false, false, 4, 16},
    {"BC3_SRGB", 0, 4, false, true, false, false, false, 4, 16},
    {"BC4", 0, 1, false, false, false, false, false, 4, 8},
    {"BC5", 0, 2, false, false, false, false, false, 4, 16},
    {"BC7", 0, 4, false, false, false, false, false, 4, 16},
    {"BC7_SRGB", 0, 4, false, true, false, false, false, 4, 16},
    {"BGRA8", 4, 4},
    {"BGRA8_SRGB", 4, 4, false, true},
};
static_assert(sizeof(kFormats) / sizeof(kFormats[0]) == size_t(Format::Count));

const VertexFormatInfo kVertexFormats[] = {
    {"Float", 4, 1},     {"Float2", 8, 2},    {"Float3", 12, 3},  {"Float4", 16, 4},
    {"Half2", 4, 2},     {"Half4", 8, 4},     {"UNorm8x4", 4, 4}, {"SNorm8x4", 4, 4},
    {"UNorm16x2", 4, 2}, {"SNorm16x2", 4, 2}, {"UInt32", 4, 1},
};
static_assert(sizeof(kVertexFormats) / sizeof(kVertexFormats[0]) == size_t(VertexFormat::Count));
}  // namespace

const FormatInfo& formatInfo(Format f) {
    size_t i = size_t(f);
    return i < size_t(Format::Count) ? kFormats[i] : kFormats[0];
}

uint64_t imageByteSize(Format f, uint32_t width, uint32_t height) {
    const FormatInfo& i = formatInfo(f);
    if (i.blockSize > 1)
        return uint64_t((width + i.blockSize - 1) / i.blockSize) *
               ((height + i.blockSize - 1) / i.blockSize) * i.bytesPerBlock;
    return uint64_t(width) * height * i.bytesPerPixel;
}

uint32_t aspectTexelBytes(Format f, TextureAspect aspect) {
    const FormatInfo& i = formatInfo(f);
    const bool depth = aspect == TextureAspect::Depth ||
                       (aspect == TextureAspect::All && i.hasDepth && !i.hasStencil);
    const bool stencil = aspect == TextureAspect::Stencil ||
                         (aspect == TextureAspect::All && i.hasStencil && !i.hasDepth);
    if (!i.hasDepth && !i.hasStencil) return aspect == TextureAspect::All ? i.bytesPerPixel : 0;
    if (depth) return !i.hasDepth ? 0 : f == Format::D16 ? 2 : 4;
    if (stencil) return i.hasStencil ? 1 : 0;
    return 0;  // All of a format with two aspects
}

Format formatFromName(std::string_view name) {
    for (size_t i = 1; i < size_t(Format::Count); ++i)
        if (kFormats[i].name == name) return Format(i);
    return Format::Undefined;
}

const VertexFormatInfo& vertexFormatInfo(VertexFormat f) {
    size_t i = size_t(f);
    static const VertexFormatInfo invalid{"Invalid", 0, 0};
    return i < size_t(VertexFormat::Count) ? kVertexFormats[i] : invalid;
}

Format srgbPair(Format f) {
    switch (f) {
        case Format::RGBA8:
            return Format::RGBA8_SRGB;
        case Format::RGBA8_SRGB:
            return Format::RGBA8;
        case Format::BC1:
            return Format::BC1_SRGB;
        case Format::BC1_SRGB:
            return Format::BC1;
        case Format::BC3:
            return Format::BC3_SRGB;
        case Format::BC3_SRGB:
            return Format::BC3;
        case Format::BC7:
            return Format::BC7_SRGB;
        case Format::BC7_SRGB:
            return Format::BC7;
        case Format::BGRA8:
            return Format::BGRA8_SRGB;
        case Format::BGRA8_SRGB:
            return Format::BGRA8;
        default:
            return Format::Undefined;
    }
}

// BGRA8 texels keep their bytes only among the BGRA8 formats: GL stores them as RGBA, so a
// copy or view into another 4-byte format would see the bytes differently there.
static bool isBgra(Format f) { return f == Format::BGRA8 || f == Format::BGRA8_SRGB; }

bool channelOrdersDiffer(Format a, Format b) {
    auto isRgba = [](Format f) { return f == Format::RGBA8 || f == Format::RGBA8_SRGB; };
    return (isBgra(a) && isRgba(b)) || (isRgba(a) && isBgra(b));
}

bool viewFormatsCompatible(Format a, Format b) {
    return formatsCompatible(a, b) || channelOrdersDiffer(a, b);
}

bool formatsCompatible(Format a, Format b) {
    if (a == b || (srgbPair(a) == b && b != Format::Undefined)) return true;
    if (isBgra(a) || isBgra(b)) return false;
    const FormatInfo &fa = formatInfo(a), &fb = formatInfo(b);
    return !isDepthFormat(a) && !isDepthFormat(b) && !isCompressedFormat(a) &&
           !isCompressedFormat(b) && a != Format::Undefined && b != Format::Undefined &&
           fa.bytesPerPixel == fb.bytesPerPixel;
}

}  // namespace fe::gdi
