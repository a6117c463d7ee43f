// Shared validation: Explicit barriers: the states and accesses a resource's usage allows.
#include "ValidationSupport.h"

namespace fe::gdi::validate {

namespace {

// A state the texture's usage and format allow. Undefined always (contents not needed), and the
// copy states always: the device's own transfers (writeTexture, readTexture) copy any texture,
// so "it was last written by writeTexture" is a true CopyDst whatever the usage.
void stateAllowed(const TextureDesc& d, ResourceState s, const std::string& name) {
    const bool depth = isDepthFormat(d.format);
    auto need = [&](TextureUsage u) {
        textureUsage(d, u, name,
                     (std::string("barrier to or from ") + resourceStateName(s)).c_str());
    };
    switch (s) {
        case ResourceState::Undefined:
            return;
        case ResourceState::RenderTarget:
        case ResourceState::DepthTarget:
            need(TextureUsage::RenderTarget);
            if (depth != (s == ResourceState::DepthTarget))
                throw Error("barrier: " + describeObject("texture", name, {}) + " has format " +
                            std::string(formatInfo(d.format).name) + ": its attachment state is " +
                            (depth ? "DepthTarget" : "RenderTarget"));
            return;
        case ResourceState::ShaderRead:
            return need(TextureUsage::Sampled | TextureUsage::Storage);
        case ResourceState::Storage:
            return need(TextureUsage::Storage);
        case ResourceState::CopySrc:
        case ResourceState::CopyDst:
            return;
    }
}

// Each access of a barrier needs the usage that allows it; the copy accesses need none (the
// device's writeBuffer and readBuffer copy any buffer, as for textures above).
void accessesAllowed(const BufferDesc& d, BufferAccess a, const std::string& name) {
    using A = BufferAccess;
    using U = BufferUsage;
    static constexpr std::pair<A, U> kNeeds[] = {
        {A::Vertex, U::Vertex},   {A::Index, U::Index},         {A::Indirect, U::Indirect},
        {A::Uniform, U::Uniform}, {A::StorageRead, U::Storage}, {A::StorageWrite, U::Storage}};
    for (const auto& [access, usage] : kNeeds)
        if (any(a, access)) bufferUsage(d, usage, name, "barrier");
}

}  // namespace

SubresourceRange textureBarrier(const TextureDesc& d, const TextureBarrier& b,
                                const std::string& name) {
    if (b.after == ResourceState::Undefined)
        throw Error("barrier: a texture cannot go to Undefined");
    stateAllowed(d, b.before, name);
    stateAllowed(d, b.after, name);
    const uint32_t layers = d.dimension == TextureDimension::Texture3D ? 1 : d.depthOrLayers;
    SubresourceRange r{
        b.baseMip, b.mipCount ? b.mipCount : d.mipLevels - std::min(b.baseMip, d.mipLevels),
        b.baseLayer, b.layerCount ? b.layerCount : layers - std::min(b.baseLayer, layers)};
    if (b.baseMip >= d.mipLevels || r.mipCount == 0 ||
        uint64_t(r.baseMip) + r.mipCount > d.mipLevels || b.baseLayer >= layers ||
        r.layerCount == 0 || uint64_t(r.baseLayer) + r.layerCount > layers)
        throw Error("barrier: " + describeObject("texture", name, {}) + " has mips 0-" +
                    std::to_string(d.mipLevels - 1) + " and layers 0-" +
                    std::to_string(layers - 1) + "; the barrier names mips " +
                    std::to_string(b.baseMip) + "+" + std::to_string(b.mipCount) + ", layers " +
                    std::to_string(b.baseLayer) + "+" + std::to_string(b.layerCount));
    r.whole =
        r.baseMip == 0 && r.mipCount == d.mipLevels && r.baseLayer == 0 && r.layerCount == layers;
    return r;
}

uint64_t bufferBarrier(const BufferDesc& d, const BufferBarrier& b, const std::string& name) {
    accessesAllowed(d, b.before, name);
    accessesAllowed(d, b.after, name);
    const uint64_t size = b.size ? b.size : d.size - std::min(b.offset, d.size);
    if (b.offset >= d.size || size > d.size - b.offset)
        throw Error("barrier: range " + std::to_string(b.offset) + "+" + std::to_string(b.size) +
                    " is outside " +
                    describeObject("buffer", name, std::to_string(d.size) + " bytes"));
    return size;
}

}  // namespace fe::gdi::validate
