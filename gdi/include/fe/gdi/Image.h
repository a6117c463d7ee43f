// Layer 1 (Primitives): a CPU-side image, what readback returns and what tests compare.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "fe/gdi/Format.h"

namespace fe::gdi {

struct Image {
    uint32_t width = 0;
    uint32_t height = 0;
    Format format = Format::Undefined;
    std::vector<uint8_t> data;  // tightly packed rows, top to bottom

    size_t rowBytes() const;
    // Decoded texel as stored: unorm in [0,1], floats as floats; sRGB is NOT decoded.
    std::array<float, 4> texel(uint32_t x, uint32_t y) const;
    static Image fromTexels(uint32_t width, uint32_t height, Format format,
                            const std::vector<std::array<float, 4>>& texels);
};

// 8-bit sRGB PNG: stored values for 8-bit formats, sRGB_OETF(clamp(exposure x v)) for floats.
// alpha: an RGBA PNG with the image's fourth channel as stored (1 where it has none).
void writePng(const Image& image, const std::string& path, float exposure = 1.0f,
              bool alpha = false);
// Portable Float Map, linear RGB, little-endian (scale -1), rows bottom to top.
void writePfm(const Image& image, const std::string& path);

struct ImageDiff {
    uint32_t pixels = 0;
    uint32_t pixelsOverTolerance = 0;
    double maxAbsError = 0;  // in channel units (0..1 for unorm)
    double maxRelError = 0;  // |a-b| / max(|a|,|b|, floor), for float formats
    double fractionOver() const { return pixels ? double(pixelsOverTolerance) / pixels : 0.0; }
};

// Per-channel comparison. A pixel is "over" when any channel differs by more than
// absTolerance AND (relTolerance <= 0 or more than relTolerance relative to the larger value).
ImageDiff compareImages(const Image& a, const Image& b, double absTolerance,
                        double relTolerance = 0.0, Image* diffImage = nullptr);

}  // namespace fe::gdi
