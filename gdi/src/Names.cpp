// Names of gdi enums, for messages and dumps.
#include "fe/gdi/Device.h"

namespace fe::gdi {

const char* queueKindName(QueueKind q) {
    switch (q) {
        case QueueKind::Graphics:
            return "graphics";
        case QueueKind::Compute:
            return "compute";
        case QueueKind::Copy:
            return "copy";
    }
    return "unknown";
}

const char* resourceStateName(ResourceState s) {
    switch (s) {
        case ResourceState::Undefined:
            return "Undefined";
        case ResourceState::RenderTarget:
            return "RenderTarget";
        case ResourceState::DepthTarget:
            return "DepthTarget";
        case ResourceState::ShaderRead:
            return "ShaderRead";
        case ResourceState::Storage:
            return "Storage";
        case ResourceState::CopySrc:
            return "CopySrc";
        case ResourceState::CopyDst:
            return "CopyDst";
    }
    return "?";
}

const char* textureDimensionName(TextureDimension d) {
    switch (d) {
        case TextureDimension::Texture2D:
            return "Texture2D";
        case TextureDimension::Texture2DArray:
            return "Texture2DArray";
        case TextureDimension::TextureCube:
            return "TextureCube";
        case TextureDimension::TextureCubeArray:
            return "TextureCubeArray";
        case TextureDimension::Texture3D:
            return "Texture3D";
    }
    return "?";
}

const char* textureKindName(uint8_t kind) {
    if (kind == kTexture2DMultisampleKind) return "Texture2D (multisampled)";
    return kind == 0 || kind > kTexture2DMultisampleKind
               ? "?"
               : textureDimensionName(TextureDimension(kind - 1));
}

const char* queryTypeName(QueryType t) {
    switch (t) {
        case QueryType::Occlusion:
            return "Occlusion";
        case QueryType::AnySamplesPassed:
            return "AnySamplesPassed";
        case QueryType::PipelineStatistics:
            return "PipelineStatistics";
        case QueryType::Timestamp:
            return "Timestamp";
    }
    return "?";
}

}  // namespace fe::gdi
