#include "assets/JpegDecode.h"

#include <turbojpeg.h>

#include <memory>
#include <stdexcept>

namespace fe::assets {

bool looksLikeJpeg(const unsigned char* bytes, size_t size) {
    return size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF;
}

JpegImage decodeJpeg(const unsigned char* bytes, size_t size, uint64_t maxPixels) {
    if (size > size_t(UINT32_MAX)) throw std::runtime_error("encoded JPEG too large");
    std::unique_ptr<void, int (*)(tjhandle)> tj(tjInitDecompress(), &tjDestroy);
    if (!tj)
        throw std::runtime_error("libjpeg-turbo could not start: " +
                                 std::string(tjGetErrorStr2(nullptr)));
    auto reason = [&] { return std::string(tjGetErrorStr2(tj.get())); };

    int width = 0, height = 0, subsampling = 0, colorspace = 0;
    if (tjDecompressHeader3(tj.get(), bytes, static_cast<unsigned long>(size), &width, &height,
                            &subsampling, &colorspace) != 0) {
        throw std::runtime_error(reason());
    }
    if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > maxPixels) {
        throw std::runtime_error("unsupported image size " + std::to_string(width) + "x" +
                                 std::to_string(height));
    }
    JpegImage out;
    out.width = uint32_t(width);
    out.height = uint32_t(height);
    out.rgba.resize(size_t(width) * size_t(height) * 4);
    // Warnings (a truncated scan, say) are errors too: a half-decoded texture is silent garbage.
    constexpr int kFlags = TJFLAG_STOPONWARNING | TJFLAG_LIMITSCANS | TJFLAG_ACCURATEDCT;
    if (tjDecompress2(tj.get(), bytes, static_cast<unsigned long>(size), out.rgba.data(), width, 0,
                      height, TJPF_RGBA, kFlags) != 0) {
        throw std::runtime_error(reason());
    }
    return out;
}

}  // namespace fe::assets
