// Layer 5: Radiance HDR decoding by stb_image, whose implementation lives (static) in the one
// translation unit that also holds tinygltf's (GltfLoader.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace fe::assets {

struct HdrImage {
    uint32_t width = 0, height = 0;
    std::vector<float> rgb;  // rows top to bottom
};
// Throws AssetError naming the file and stb_image's reason.
HdrImage decodeRadianceHdr(const std::string& path);

}  // namespace fe::assets
