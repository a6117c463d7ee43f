// gdi formats and enums to their Vulkan equivalents.
#include <string>

#include "VulkanDevice.h"
#include "fe/gdi/Validation.h"

namespace fe::vk {

void throwVk(VkResult r, const char* what, const std::string& object) {
    const char* name = "unknown error";
    switch (r) {
        case VK_ERROR_OUT_OF_HOST_MEMORY:
            name = "VK_ERROR_OUT_OF_HOST_MEMORY";
            break;
        case VK_ERROR_OUT_OF_DEVICE_MEMORY:
            name = "VK_ERROR_OUT_OF_DEVICE_MEMORY";
            break;
        case VK_ERROR_INITIALIZATION_FAILED:
            name = "VK_ERROR_INITIALIZATION_FAILED";
            break;
        case VK_ERROR_DEVICE_LOST:
            name = "VK_ERROR_DEVICE_LOST";
            break;
        case VK_ERROR_LAYER_NOT_PRESENT:
            name = "VK_ERROR_LAYER_NOT_PRESENT";
            break;
        case VK_ERROR_EXTENSION_NOT_PRESENT:
            name = "VK_ERROR_EXTENSION_NOT_PRESENT";
            break;
        case VK_ERROR_FEATURE_NOT_PRESENT:
            name = "VK_ERROR_FEATURE_NOT_PRESENT";
            break;
        case VK_ERROR_INCOMPATIBLE_DRIVER:
            name = "VK_ERROR_INCOMPATIBLE_DRIVER (no Vulkan ICD installed?)";
            break;
        case VK_ERROR_FORMAT_NOT_SUPPORTED:
            name = "VK_ERROR_FORMAT_NOT_SUPPORTED";
            break;
        case VK_ERROR_INVALID_SHADER_NV:
            name = "VK_ERROR_INVALID_SHADER_NV";
            break;
        case VK_TIMEOUT:
            name = "VK_TIMEOUT";
            break;
        default:
            break;
    }
    const std::string message = std::string("Vulkan: ") + what + " failed" +
                                (object.empty() ? "" : " for " + object) + ": " + name + " (" +
                                std::to_string(int(r)) + ")";
    if (r == VK_ERROR_DEVICE_LOST) throw gdi::DeviceLostError(message);
    throw gdi::Error(message);
}

VkFormat toVkFormat(gdi::Format f) {
    using F = gdi::Format;
    switch (f) {
        case F::RGBA8:
            return VK_FORMAT_R8G8B8A8_UNORM;
        case F::RGBA8_SRGB:
            return VK_FORMAT_R8G8B8A8_SRGB;
        case F::BGRA8:
            return VK_FORMAT_B8G8R8A8_UNORM;
        case F::BGRA8_SRGB:
            return VK_FORMAT_B8G8R8A8_SRGB;
        case F::RGBA16F:
            return VK_FORMAT_R16G16B16A16_SFLOAT;
        case F::RG16F:
            return VK_FORMAT_R16G16_SFLOAT;
        case F::R16F:
            return VK_FORMAT_R16_SFLOAT;
        case F::RGBA32F:
            return VK_FORMAT_R32G32B32A32_SFLOAT;
        case F::RG32F:
            return VK_FORMAT_R32G32_SFLOAT;
        case F::R32F:
            return VK_FORMAT_R32_SFLOAT;
        case F::R32U:
            return VK_FORMAT_R32_UINT;
        case F::R11G11B10F:
            return VK_FORMAT_B10G11R11_UFLOAT_PACK32;
        case F::D32F:
            return VK_FORMAT_D32_SFLOAT;
        case F::D24S8:
            return VK_FORMAT_D24_UNORM_S8_UINT;
        case F::D16:
            return VK_FORMAT_D16_UNORM;
        case F::D32F_S8:
            return VK_FORMAT_D32_SFLOAT_S8_UINT;
        case F::S8:
            return VK_FORMAT_S8_UINT;
        case F::BC1:
            return VK_FORMAT_BC1_RGBA_UNORM_BLOCK;
        case F::BC1_SRGB:
            return VK_FORMAT_BC1_RGBA_SRGB_BLOCK;
        case F::BC3:
            return VK_FORMAT_BC3_UNORM_BLOCK;
        case F::BC3_SRGB:
            return VK_FORMAT_BC3_SRGB_BLOCK;
        case F::BC4:
            return VK_FORMAT_BC4_UNORM_BLOCK;
        case F::BC5:
            return VK_FORMAT_BC5_UNORM_BLOCK;
        case F::BC7:
            return VK_FORMAT_BC7_UNORM_BLOCK;
        case F::BC7_SRGB:
            return VK_FORMAT_BC7_SRGB_BLOCK;
        default:
            return VK_FORMAT_UNDEFINED;
    }
}

VkFormat toVkVertexFormat(gdi::VertexFormat f) {
    using V = gdi::VertexFormat;
    switch (f) {
        case V::Float:
            return VK_FORMAT_R32_SFLOAT;
        case V::Float2:
            return VK_FORMAT_R32G32_SFLOAT;
        case V::Float3:
            return VK_FORMAT_R32G32B32_SFLOAT;
        case V::Float4:
            return VK_FORMAT_R32G32B32A32_SFLOAT;
        case V::Half2:
            return VK_FORMAT_R16G16_SFLOAT;
        case V::Half4:
            return VK_FORMAT_R16G16B16A16_SFLOAT;
        case V::UNorm8x4:
            return VK_FORMAT_R8G8B8A8_UNORM;
        case V::SNorm8x4:
            return VK_FORMAT_R8G8B8A8_SNORM;
        case V::UNorm16x2:
            return VK_FORMAT_R16G16_UNORM;
        case V::SNorm16x2:
            return VK_FORMAT_R16G16_SNORM;
        case V::UInt32:
            return VK_FORMAT_R32_UINT;
        default:
            return VK_FORMAT_UNDEFINED;
    }
}

VkImageAspectFlags aspectOf(gdi::Format f) {
    const auto& fi = gdi::formatInfo(f);
    if (fi.hasDepth)
        return VK_IMAGE_ASPECT_DEPTH_BIT | (fi.hasStencil ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
    return fi.hasStencil ? VK_IMAGE_ASPECT_STENCIL_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

VkImageAspectFlags viewAspectOf(gdi::Format f) {
    const auto& fi = gdi::formatInfo(f);
    return fi.hasDepth     ? VK_IMAGE_ASPECT_DEPTH_BIT
           : fi.hasStencil ? VK_IMAGE_ASPECT_STENCIL_BIT
                           : VK_IMAGE_ASPECT_COLOR_BIT;
}

uint32_t arrayLayers(const gdi::TextureDesc& d) {
    return d.dimension == gdi::TextureDimension::Texture3D ? 1 : d.depthOrLayers;
}

VkBufferImageCopy copyRegion(const gdi::TextureDesc& d, gdi::Subresource at,
                             VkDeviceSize bufferOffset) {
    const gdi::validate::Extent3 e = gdi::validate::mipExtent(d, at.mipLevel);
    const bool is3D = d.dimension == gdi::TextureDimension::Texture3D;
    VkBufferImageCopy r{};
    r.bufferOffset = bufferOffset;
    r.imageSubresource = {viewAspectOf(d.format), at.mipLevel, is3D ? 0 : at.layer, 1};
    r.imageOffset = {0, 0, is3D ? int32_t(at.layer) : 0};
    r.imageExtent = {e.width, e.height, 1};
    return r;
}

VkBufferImageCopy regionCopy(const gdi::TextureDesc& d, const gdi::TextureRegion& r,
                             const gdi::TexelLayout& l) {
    const gdi::FormatInfo& fi = gdi::formatInfo(d.format);
    const uint32_t unit =
        fi.blockSize > 1 ? fi.bytesPerBlock : gdi::aspectTexelBytes(d.format, r.aspect);
    const bool is3D = d.dimension == gdi::TextureDimension::Texture3D;
    VkImageAspectFlags aspect = viewAspectOf(d.format);
    if (r.aspect == gdi::TextureAspect::Depth) aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    if (r.aspect == gdi::TextureAspect::Stencil) aspect = VK_IMAGE_ASPECT_STENCIL_BIT;
    VkBufferImageCopy c{};
    c.bufferOffset = l.offset;
    c.bufferRowLength = l.bytesPerRow / unit * fi.blockSize;  // in texels
    c.bufferImageHeight = l.rowsPerImage * fi.blockSize;
    c.imageSubresource = {aspect, r.mipLevel, is3D ? 0 : r.z, is3D ? 1 : r.depth};
    c.imageOffset = {int32_t(r.x), int32_t(r.y), is3D ? int32_t(r.z) : 0};
    c.imageExtent = {r.width, r.height, is3D ? r.depth : 1};
    return c;
}

VkImageCopy imageCopy(const gdi::TextureDesc& dst, const gdi::TextureRegion& d,
                      const gdi::TextureDesc& src, const gdi::TextureRegion& s) {
    const bool is3D = src.dimension == gdi::TextureDimension::Texture3D;
    VkImageCopy c{};
    c.srcSubresource = {viewAspectOf(src.format), s.mipLevel, is3D ? 0 : s.z, is3D ? 1 : s.depth};
    c.srcOffset = {int32_t(s.x), int32_t(s.y), is3D ? int32_t(s.z) : 0};
    c.dstSubresource = {viewAspectOf(dst.format), d.mipLevel, is3D ? 0 : d.z, is3D ? 1 : d.depth};
    c.dstOffset = {int32_t(d.x), int32_t(d.y), is3D ? int32_t(d.z) : 0};
    c.extent = {s.width, s.height, is3D ? s.depth : 1};
    return c;
}

}  // namespace fe::vk
