// Layer 7: the G-buffer the deferred techniques share: base colour + metallic, world normal +
// roughness, emissive + unlit flag, and the scene depth, written by one geometry pass.
#pragma once
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
};

}  // namespace fe::render
