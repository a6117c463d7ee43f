// The one translation unit with stb_image's implementation, made static (see ImageDecode.h).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_NO_JPEG  // JPEG goes to libjpeg-turbo (JpegDecode.h says why)
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include "assets/ImageDecode.h"

#include <climits>
#include <stdexcept>

#include "assets/AssetError.h"

namespace fe::assets {

DecodedImage decodeImage(const unsigned char* bytes, size_t size, uint64_t maxPixels) {
    if (size > size_t(INT_MAX)) throw std::runtime_error("encoded image too large");
    const int len = int(size);
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, len, &w, &h, &comp)) {
        const char* why = stbi_failure_reason();
        throw std::runtime_error(why ? why : "unknown format");
    }
    if (w <= 0 || h <= 0 || uint64_t(w) * uint64_t(h) > maxPixels)
        throw std::runtime_error("unsupported image size " + std::to_string(w) + "x" +
                                 std::to_string(h));
    unsigned char* px = stbi_load_from_memory(bytes, len, &w, &h, &comp, 4);
    if (!px) {
        const char* why = stbi_failure_reason();
        throw std::runtime_error(why ? why : "unknown error");
    }
    DecodedImage out{uint32_t(w), uint32_t(h),
                     std::vector<unsigned char>(px, px + size_t(w) * size_t(h) * 4)};
    stbi_image_free(px);
    return out;
}

HdrImage decodeRadianceHdr(const std::string& path) {
    int w = 0, h = 0, comp = 0;
    float* px = stbi_loadf(path.c_str(), &w, &h, &comp, 3);
    if (!px)
        throw AssetError(
            path + ": cannot read the Radiance HDR image: " + std::string(stbi_failure_reason()));
    HdrImage img{uint32_t(w), uint32_t(h), std::vector<float>(px, px + size_t(w) * h * 3)};
    stbi_image_free(px);
    return img;
}

}  // namespace fe::assets
