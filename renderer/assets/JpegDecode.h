// Layer 5: JPEG decoding by libjpeg-turbo (libturbojpeg0-dev).
// Why not stb_image: Debian 12's stb_image (2022-09-08) writes past its Huffman tables when a
// DHT segment declares more than 256 codes (found by our glTF fuzzer); libjpeg-turbo is fuzzed
// upstream continuously and also bounds progressive scans (TJFLAG_LIMITSCANS), so a hostile
// file ends in an error, not a write out of bounds or an endless decode.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fe::assets {

// True when the bytes start with a JPEG start-of-image marker followed by another marker.
bool looksLikeJpeg(const unsigned char* bytes, size_t size);

struct JpegImage {
    uint32_t width = 0, height = 0;
    std::vector<unsigned char> rgba;  // rows top to bottom, 4 bytes a pixel, alpha 255
};
// Decodes to RGBA8. Throws std::runtime_error with libjpeg-turbo's reason, or when the header
// declares more than maxPixels pixels (checked before any pixel memory is allocated).
JpegImage decodeJpeg(const unsigned char* bytes, size_t size, uint64_t maxPixels);

}  // namespace fe::assets
