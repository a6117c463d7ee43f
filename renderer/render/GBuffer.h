// Layer 7: the G-buffer the deferred techniques share: base colour + metallic, world normal +
// roughness, emissive + unlit flag, and the scene depth, written by one geometry pass (20 bytes
// a pixel and depth). When the frame is lit by its environment and a material has an occlusion
// texture, a fourth target holds the occlusion (1 + strength (ao - 1), R16F: 22 bytes a pixel),
// which the image-based lighting pass multiplies by; otherwise that pass reads 1x1 white.
#pragma once
#include "render/TechniqueRenderer.h"

namespace fe::render {

struct GBuffer {
    static constexpr gdi::Format kFormat0 = gdi::Format::RGBA8_SRGB,
                                 kFormat1 = gdi::Format::RGBA16F, kFormat2 = gdi::Format::RGBA16F,
                                 kFormat3 = gdi::Format::R16F;
    graph::TextureId gb0, gb1, gb2, gb3, depth;  // gb3: only with occlusion and image-based light
    gdi::TextureHandle noOcclusion;              // bound in gb3's place without it

    // Declares the textures and the "gbuffer" pass writing them.
    void declare(graph::RenderGraph& g, TechniqueContext& ctx, graph::TextureId sceneDepth);
    // Binds the G-buffer (base colour only when `albedo`) and depth at their shader slots.
    void bind(gdi::CommandList& cmd, const graph::PassContext& pc, gdi::SamplerHandle sampler,
              bool albedo) const;
    void sampleIn(graph::PassBuilder& b, bool albedo) const;
    // The occlusion (gb3, or white) at kSlotGBuffer3, for the image-based lighting pass.
    void bindOcclusion(gdi::CommandList& cmd, const graph::PassContext& pc,
                       gdi::SamplerHandle sampler) const;
    void sampleOcclusionIn(graph::PassBuilder& b) const;
};

}  // namespace fe::render
