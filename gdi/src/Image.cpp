#include "fe/gdi/Image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBIW_ASSERT(x) ((void)0)
#include <stb_image_write.h>

#include "fe/gdi/Device.h"

namespace fe::gdi {

namespace {

float halfToFloat(uint16_t h) {
    uint32_t sign = (h >> 15) & 1, exp = (h >> 10) & 0x1f, man = h & 0x3ff;
    float v;
    if (exp == 0)
        v = std::ldexp(float(man), -24);
    else if (exp == 31)
        v = man ? NAN : INFINITY;
    else
        v = std::ldexp(float(man | 0x400), int(exp) - 25);
    return sign ? -v : v;
}

uint16_t floatToHalf(float f) {
    uint32_t x;
    std::memcpy(&x, &f, 4);
    uint32_t sign = (x >> 16) & 0x8000;
    if (std::isnan(f)) return uint16_t(sign | 0x7e00);
    float a = std::fabs(f);
    if (a >= 65520.0f) return uint16_t(sign | 0x7c00);
    if (a < std::ldexp(1.0f, -24) * 0.5f) return uint16_t(sign);
    int e;
    float m = std::frexp(a, &e);  // a = m * 2^e, m in [0.5,1)
    int exp = e - 1 + 15;
    if (exp <= 0) {  // subnormal half
        uint32_t man = uint32_t(std::nearbyint(std::ldexp(a, 24)));
        return uint16_t(sign | man);
    }
    uint32_t man = uint32_t(std::nearbyint((m * 2.0f - 1.0f) * 1024.0f));
    if (man == 1024) {
        man = 0;
        ++exp;
    }
    if (exp >= 31) return uint16_t(sign | 0x7c00);
    return uint16_t(sign | (uint32_t(exp) << 10) | man);
}

// Unsigned small floats of R11G11B10F: 5-bit exponent, `bits`-bit mantissa, no sign.
float smallFloat(uint32_t v, int bits) {
    uint32_t exp = v >> bits, man = v & ((1u << bits) - 1);
    if (exp == 0) return std::ldexp(float(man), -14 - bits);
    if (exp == 31) return man ? NAN : INFINITY;
    return std::ldexp(float(man | (1u << bits)), int(exp) - 15 - bits);
}

uint32_t toSmallFloat(float f, int bits) {
    if (!(f > 0)) return 0;
    if (std::isinf(f)) return 31u << bits;
    int e;
    std::frexp(f, &e);
    int exp = e - 1 + 15;
    if (exp <= 0) return uint32_t(std::nearbyint(std::ldexp(f, 14 + bits))) & ((1u << bits) - 1);
    uint32_t man = uint32_t(std::nearbyint((std::ldexp(f, -(e - 1)) - 1.0f) * float(1u << bits)));
    if (man == (1u << bits)) {
        man = 0;
        ++exp;
    }
    if (exp >= 31) return (30u << bits) | ((1u << bits) - 1);  // clamp to max finite
    return (uint32_t(exp) << bits) | man;
}

float linearToSrgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

size_t Image::rowBytes() const { return size_t(width) * formatInfo(format).bytesPerPixel; }

std::array<float, 4> Image::texel(uint32_t x, uint32_t y) const {
    std::array<float, 4> out{0, 0, 0, 1};
    const uint8_t* p = data.data() + y * rowBytes() + size_t(x) * formatInfo(format).bytesPerPixel;
    auto f32 = [&](int i) {
        float v;
        std::memcpy(&v, p + 4 * i, 4);
        return v;
    };
    auto f16 = [&](int i) {
        uint16_t v;
        std::memcpy(&v, p + 2 * i, 2);
        return halfToFloat(v);
    };
    switch (format) {
        case Format::RGBA8:
        case Format::RGBA8_SRGB:
            for (int i = 0; i < 4; ++i) out[i] = p[i] / 255.0f;
            break;
        case Format::BGRA8:
        case Format::BGRA8_SRGB:
            for (int i = 0; i < 4; ++i) out[i] = p[i == 3 ? 3 : 2 - i] / 255.0f;
            break;
        case Format::RGBA16F:
            for (int i = 0; i < 4; ++i) out[i] = f16(i);
            break;
        case Format::RG16F:
            out[0] = f16(0);
            out[1] = f16(1);
            out[2] = 0;
            break;
        case Format::R16F:
            out[0] = f16(0);
            out[1] = out[2] = 0;
            break;
        case Format::RGBA32F:
            for (int i = 0; i < 4; ++i) out[i] = f32(i);
            break;
        case Format::RG32F:
            out[0] = f32(0);
            out[1] = f32(1);
            out[2] = 0;
            break;
        case Format::R32F:
        case Format::D32F:
            out[0] = f32(0);
            out[1] = out[2] = 0;
            break;
        case Format::R32U: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            out[0] = float(v);
            out[1] = out[2] = 0;
            break;
        }
        case Format::R11G11B10F: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            out[0] = smallFloat(v & 0x7ff, 6);
            out[1] = smallFloat((v >> 11) & 0x7ff, 6);
            out[2] = smallFloat((v >> 22) & 0x3ff, 5);
            break;
        }
        case Format::
            D24S8: {  // depth in the low 24 bits, stencil in the high 8 (Vulkan copy layout)
            uint32_t v;
            std::memcpy(&v, p, 4);
            out[0] = float(v & 0xffffff) / float(0xffffff);
            out[1] = float(v >> 24);
            out[2] = 0;
            break;
        }
        case Format::D16: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            out[0] = float(v) / 65535.0f;
            out[1] = out[2] = 0;
            break;
        }
        case Format::S8:
            out[0] = 0;
            out[1] = float(p[0]);
            out[2] = 0;
            break;  // stencil in [1], as with depth
        case Format::
            D32F_S8: {  // float depth, then stencil in the low 8 bits of the next word (GL's layout)
            uint32_t s;
            std::memcpy(&s, p + 4, 4);
            out[0] = f32(0);
            out[1] = float(s & 0xff);
            out[2] = 0;
            break;
        }
        default:
            break;
    }
    return out;
}

Image Image::fromTexels(uint32_t width, uint32_t height, Format format,
                        const std::vector<std::array<float, 4>>& texels) {
    Image img{width, height, format, {}};
    const uint32_t bpp = formatInfo(format).bytesPerPixel;
    if (bpp == 0) throw Error("Image::fromTexels: format has no pixel size");
    if (texels.size() != size_t(width) * height)
        throw Error("Image::fromTexels: texel count does not match the size");
    img.data.resize(size_t(width) * height * bpp);
    for (size_t i = 0; i < texels.size(); ++i) {
        uint8_t* p = img.data.data() + i * bpp;
        const auto& t = texels[i];
        auto put32 = [&](int c, float v) { std::memcpy(p + 4 * c, &v, 4); };
        auto put16 = [&](int c, float v) {
            uint16_t h = floatToHalf(v);
            std::memcpy(p + 2 * c, &h, 2);
        };
        switch (format) {
            case Format::RGBA8:
            case Format::RGBA8_SRGB:
                for (int c = 0; c < 4; ++c)
                    p[c] = uint8_t(std::nearbyint(std::clamp(t[c], 0.0f, 1.0f) * 255.0f));
                break;
            case Format::BGRA8:
            case Format::BGRA8_SRGB:
                for (int c = 0; c < 4; ++c)
                    p[c == 3 ? 3 : 2 - c] =
                        uint8_t(std::nearbyint(std::clamp(t[c], 0.0f, 1.0f) * 255.0f));
                break;
            case Format::RGBA16F:
                for (int c = 0; c < 4; ++c) put16(c, t[c]);
                break;
            case Format::RG16F:
                put16(0, t[0]);
                put16(1, t[1]);
                break;
            case Format::R16F:
                put16(0, t[0]);
                break;
            case Format::RGBA32F:
                for (int c = 0; c < 4; ++c) put32(c, t[c]);
                break;
            case Format::RG32F:
                put32(0, t[0]);
                put32(1, t[1]);
                break;
            case Format::R32F:
            case Format::D32F:
                put32(0, t[0]);
                break;
            case Format::R32U: {
                uint32_t v = uint32_t(std::max(0.0f, t[0]));
                std::memcpy(p, &v, 4);
                break;
            }
            case Format::R11G11B10F: {
                uint32_t v = toSmallFloat(t[0], 6) | (toSmallFloat(t[1], 6) << 11) |
                             (toSmallFloat(t[2], 5) << 22);
                std::memcpy(p, &v, 4);
                break;
            }
            case Format::D24S8: {
                uint32_t v = uint32_t(std::nearbyint(std::clamp(t[0], 0.0f, 1.0f) * 0xffffff)) |
                             (uint32_t(t[1]) << 24);
                std::memcpy(p, &v, 4);
                break;
            }
            case Format::D16: {
                const auto v = uint16_t(std::nearbyint(std::clamp(t[0], 0.0f, 1.0f) * 65535.0f));
                std::memcpy(p, &v, 2);
                break;
            }
            case Format::S8:
                p[0] = uint8_t(std::clamp(t[1], 0.0f, 255.0f));
                break;
            case Format::D32F_S8: {
                put32(0, t[0]);
                const uint32_t s = uint32_t(std::clamp(t[1], 0.0f, 255.0f)) & 0xff;
                std::memcpy(p + 4, &s, 4);
                break;
            }
            default:
                break;
        }
    }
    return img;
}

void writePng(const Image& image, const std::string& path, float exposure, bool alpha) {
    const FormatInfo& fi = formatInfo(image.format);
    if (image.width == 0 || image.height == 0 ||
        image.data.size() < image.rowBytes() * image.height)
        throw Error("writePng: empty or truncated image for " + path);
    const int channels = alpha ? 4 : 3;
    std::vector<uint8_t> rgb(size_t(image.width) * image.height * channels);
    const bool eightBit = image.format == Format::RGBA8 || image.format == Format::RGBA8_SRGB ||
                          image.format == Format::BGRA8 || image.format == Format::BGRA8_SRGB;
    for (uint32_t y = 0; y < image.height; ++y)
        for (uint32_t x = 0; x < image.width; ++x) {
            auto t = image.texel(x, y);
            for (int c = 0; c < channels; ++c) {
                float v = (fi.channels == 1 && !fi.hasDepth) || fi.hasDepth ? t[0] : t[c];
                if (c == 3)
                    v = fi.channels == 4 ? t[3] : 1.0f;  // alpha is stored linear, never exposed
                float enc = eightBit || c == 3 ? v : linearToSrgb(exposure * v);
                rgb[(size_t(y) * image.width + x) * channels + c] =
                    uint8_t(std::nearbyint(std::clamp(enc, 0.0f, 1.0f) * 255.0f));
            }
        }
    if (!stbi_write_png(path.c_str(), int(image.width), int(image.height), channels, rgb.data(),
                        int(image.width * channels)))
        throw Error("cannot write PNG " + path);
}

void writePfm(const Image& image, const std::string& path) {
    std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
    if (!f) throw Error("cannot write PFM " + path);
    std::fprintf(f.get(), "PF\n%u %u\n-1.0\n", image.width, image.height);
    std::vector<float> row(size_t(image.width) * 3);
    for (uint32_t yy = 0; yy < image.height; ++yy) {
        uint32_t y = image.height - 1 - yy;  // PFM stores the bottom row first
        for (uint32_t x = 0; x < image.width; ++x) {
            auto t = image.texel(x, y);
            for (int c = 0; c < 3; ++c) row[size_t(x) * 3 + c] = t[c];  // little-endian host
        }
        if (std::fwrite(row.data(), sizeof(float), row.size(), f.get()) != row.size())
            throw Error("short write to PFM " + path);
    }
}

ImageDiff compareImages(const Image& a, const Image& b, double absTolerance, double relTolerance,
                        Image* diffImage) {
    if (a.width != b.width || a.height != b.height || a.format != b.format)
        throw Error("compareImages: images differ in size or format (" + std::to_string(a.width) +
                    "x" + std::to_string(a.height) + " " + std::string(formatInfo(a.format).name) +
                    " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) + " " +
                    std::string(formatInfo(b.format).name) + ")");
    const FormatInfo& fi = formatInfo(a.format);
    // Depth formats compare depth, and stencil (texel channel 1) where they have one.
    const int channels = fi.hasStencil ? 2 : fi.hasDepth ? 1 : int(fi.channels);
    ImageDiff d;
    d.pixels = a.width * a.height;
    std::vector<std::array<float, 4>> diffTexels;
    if (diffImage) diffTexels.resize(d.pixels);
    for (uint32_t y = 0; y < a.height; ++y)
        for (uint32_t x = 0; x < a.width; ++x) {
            auto ta = a.texel(x, y), tb = b.texel(x, y);
            bool over = false;
            std::array<float, 4> dt{0, 0, 0, 1};
            for (int c = 0; c < channels; ++c) {
                double va = ta[c], vb = tb[c];
                double err = std::fabs(va - vb);
                if (std::isnan(va) != std::isnan(vb))
                    err = INFINITY;
                else if (std::isnan(va))
                    err = 0;
                else if (std::isinf(va) || std::isinf(vb))
                    err = (va == vb) ? 0 : INFINITY;
                double rel = err / std::max({std::fabs(va), std::fabs(vb), 1e-6});
                d.maxAbsError = std::max(d.maxAbsError, err);
                d.maxRelError = std::max(d.maxRelError, rel);
                // A tolerance of whole 8-bit steps holds for decoded values: 128/255 - 127/255 in
                // float is 1/255 plus rounding, which must not count as over one step.
                bool bad =
                    err > absTolerance * (1 + 1e-4) && (relTolerance <= 0 || rel > relTolerance);
                over = over || bad;
                dt[std::min(c, 2)] = float(std::min(1.0, err * 16.0));  // magnified for visibility
            }
            if (over) d.pixelsOverTolerance++;
            if (diffImage) diffTexels[size_t(y) * a.width + x] = dt;
        }
    if (diffImage) *diffImage = Image::fromTexels(a.width, a.height, Format::RGBA8, diffTexels);
    return d;
}

}  // namespace fe::gdi
