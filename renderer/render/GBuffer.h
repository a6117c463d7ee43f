// Layer 7: the G-buffer the deferred techniques share: base colour + metallic, world normal +
// roughness, emissive + unlit flag, and the scene depth, written by one geometry pass.
#pragma once
#include <vector>

#include "render/TechniqueRenderer.h"

namespace fe::render {

struct GBuffer {
    static constexpr gdi::Format kFormat0 = gdi::Format::RGBA8_SRGB, kFormat1 = gdi::Format::RGBA16F,
                                 kFormat2 = gdi::Format::RGBA16F;
    graph::TextureId gb0, gb1, gb2, depth;

    // Declares the textures and the "gbuffer" pass writing them.
    void declare(graph::RenderGraph& g, TechniqueContext& ctx, graph::TextureId sceneDepth);
    // Binds the G-buffer (base colour only when `albedo`) and depth at their shader slots.
    void bind(gdi::CommandList& cmd, const graph::PassContext& pc, gdi::SamplerHandle sampler, bool albedo) const;
    void sampleIn(graph::PassBuilder& b, bool albedo) const;
    // The binding slots bind() fills, for pipelines that read the G-buffer.
    static std::vector<gdi::BindingSlot> slots(bool albedo);
    // The same for the tiled compute passes, with the frame constants and the lights they cull.
    static std::vector<gdi::BindingSlot> computeSlots(bool albedo);
};

}  // namespace fe::render
