// The GL names of gdi values: formats, texture targets, attachment points, query targets, errors.
#include "gl/GlDevice.h"

namespace fe::gl {

namespace {
// EXT_texture_sRGB's S3TC tokens, which glcorearb.h does not carry.
constexpr GLenum kCompressedSrgbAlphaS3tcDxt1 = 0x8C4D;
constexpr GLenum kCompressedSrgbAlphaS3tcDxt5 = 0x8C4F;
}  // namespace

GlFormat toGlFormat(gdi::Format f) {
    using F = gdi::Format;
    switch (f) {
        case F::RGBA8:
            return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
        case F::RGBA8_SRGB:
            return {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE};
        // GL has no BGRA internal format: stored as RGBA, BGRA in every transfer.
        case F::BGRA8:
            return {GL_RGBA8, GL_BGRA, GL_UNSIGNED_BYTE};
        case F::BGRA8_SRGB:
            return {GL_SRGB8_ALPHA8, GL_BGRA, GL_UNSIGNED_BYTE};
        case F::RGBA16F:
            return {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT};
        case F::RG16F:
            return {GL_RG16F, GL_RG, GL_HALF_FLOAT};
        case F::R16F:
            return {GL_R16F, GL_RED, GL_HALF_FLOAT};
        case F::RGBA32F:
            return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
        case F::RG32F:
            return {GL_RG32F, GL_RG, GL_FLOAT};
        case F::R32F:
            return {GL_R32F, GL_RED, GL_FLOAT};
        case F::R32U:
            return {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT};
        case F::R11G11B10F:
            return {GL_R11F_G11F_B10F, GL_RGB, GL_UNSIGNED_INT_10F_11F_11F_REV};
        case F::D32F:
            return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
        case F::D24S8:
            return {GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8};
        case F::D16:
            return {GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT};
        case F::D32F_S8:
            return {GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV};
        case F::S8:
            return {GL_STENCIL_INDEX8, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE};
        // Compressed: the internal format only (uploads use glCompressedTextureSubImage*).
        case F::BC1:
            return {GL_COMPRESSED_RGBA_S3TC_DXT1_EXT, 0, 0};
        case F::BC1_SRGB:
            return {kCompressedSrgbAlphaS3tcDxt1, 0, 0};
        case F::BC3:
            return {GL_COMPRESSED_RGBA_S3TC_DXT5_EXT, 0, 0};
        case F::BC3_SRGB:
            return {kCompressedSrgbAlphaS3tcDxt5, 0, 0};
        case F::BC4:
            return {GL_COMPRESSED_RED_RGTC1, 0, 0};
        case F::BC5:
            return {GL_COMPRESSED_RG_RGTC2, 0, 0};
        case F::BC7:
            return {GL_COMPRESSED_RGBA_BPTC_UNORM, 0, 0};
        case F::BC7_SRGB:
            return {GL_COMPRESSED_SRGB_ALPHA_BPTC_UNORM, 0, 0};
        default:
            return {0, 0, 0};
    }
}

GLenum textureTarget(const gdi::TextureDesc& d) {
    switch (d.dimension) {
        case gdi::TextureDimension::Texture2DArray:
            return GL_TEXTURE_2D_ARRAY;
        case gdi::TextureDimension::TextureCube:
            return GL_TEXTURE_CUBE_MAP;
        case gdi::TextureDimension::TextureCubeArray:
            return GL_TEXTURE_CUBE_MAP_ARRAY;
        case gdi::TextureDimension::Texture3D:
            return GL_TEXTURE_3D;
        default:
            return d.sampleCount > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    }
}

GLenum depthAttachmentPoint(gdi::Format f) {
    const gdi::FormatInfo& fi = gdi::formatInfo(f);
    return fi.hasDepth && fi.hasStencil ? GL_DEPTH_STENCIL_ATTACHMENT
           : fi.hasDepth                ? GL_DEPTH_ATTACHMENT
                                        : GL_STENCIL_ATTACHMENT;
}

std::span<const GLenum> queryTargets(gdi::QueryType t) {
    static const GLenum occlusion[] = {GL_SAMPLES_PASSED}, any[] = {GL_ANY_SAMPLES_PASSED},
                        time[] = {GL_TIMESTAMP};
    static const GLenum statistics[] = {GL_PRIMITIVES_SUBMITTED, GL_VERTEX_SHADER_INVOCATIONS,
                                        GL_FRAGMENT_SHADER_INVOCATIONS,
                                        GL_COMPUTE_SHADER_INVOCATIONS};
    switch (t) {
        case gdi::QueryType::Occlusion:
            return occlusion;
        case gdi::QueryType::AnySamplesPassed:
            return any;
        case gdi::QueryType::Timestamp:
            return time;
        case gdi::QueryType::PipelineStatistics:
            return statistics;
    }
    return {};
}

const char* glErrorName(GLenum e) {
    switch (e) {
        case GL_OUT_OF_MEMORY:
            return "GL_OUT_OF_MEMORY";
        case GL_INVALID_ENUM:
            return "GL_INVALID_ENUM";
        case GL_INVALID_VALUE:
            return "GL_INVALID_VALUE";
        case GL_INVALID_OPERATION:
            return "GL_INVALID_OPERATION";
        case GL_CONTEXT_LOST:
            return "GL_CONTEXT_LOST";
        case GL_GUILTY_CONTEXT_RESET:
            return "GL_GUILTY_CONTEXT_RESET";
        case GL_INNOCENT_CONTEXT_RESET:
            return "GL_INNOCENT_CONTEXT_RESET";
        case GL_UNKNOWN_CONTEXT_RESET:
            return "GL_UNKNOWN_CONTEXT_RESET";
        default:
            return "GL error";
    }
}

}  // namespace fe::gl
