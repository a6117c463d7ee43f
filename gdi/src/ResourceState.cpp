#include "fe/gdi/Device.h"

namespace fe::gdi {

const char* resourceStateName(ResourceState s) {
    switch (s) {
        case ResourceState::Undefined: return "Undefined";
        case ResourceState::RenderTarget: return "RenderTarget";
        case ResourceState::DepthTarget: return "DepthTarget";
        case ResourceState::ShaderRead: return "ShaderRead";
        case ResourceState::Storage: return "Storage";
        case ResourceState::CopySrc: return "CopySrc";
        case ResourceState::CopyDst: return "CopyDst";
    }
    return "?";
}

}  // namespace fe::gdi
