// Layer 5: image decoding by stb_image (PNG, BMP, GIF, TGA, ... and Radiance HDR), whose
// implementation lives, static, in ImageDecode.cpp alone: another module embedding its own copy
// cannot clash with it at link time. JPEG goes to libjpeg-turbo instead (JpegDecode.h says why).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fe::assets {

struct DecodedImage {
    uint32_t width = 0, height = 0;
    std::vector<unsigned char> rgba;  // rows top to bottom, 4 bytes a pixel
};
// Decodes an encoded image (any format stb_image reads but JPEG) to RGBA8. Throws
// std::runtime_error with stb_image's reason, or when the header declares more than maxPixels
// pixels (checked before any pixel memory is allocated).
DecodedImage decodeImage(const unsigned char* bytes, size_t size, uint64_t maxPixels);

struct HdrImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgb;  // rows top to bottom
};
// Throws AssetError naming the file and stb_image's reason.
HdrImage decodeRadianceHdr(const std::string& path);

}  // namespace fe::assets
