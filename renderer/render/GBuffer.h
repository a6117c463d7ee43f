// Layer 7: the G-buffer the deferred techniques share: base colour + metallic, world normal +
// roughness, emissive + unlit flag, and the scene depth, written by one geometry pass (20 bytes
// a pixel and depth). When the frame is lit by its environment and a material has an occlusion
// texture, a fourth target holds the occlusion (1 + strength (ao - 1), R16F: 22 bytes a pixel),
// which the image-based lighting pass multiplies by; otherwise that pass reads 1x1 white.
// With --msaa N every target and the depth hold N samples; the geometry pass resolves the depth
// (sample 0) into the scene depth for the passes after the technique, and the lighting passes
// read the samples themselves in their FE_MULTISAMPLED variants (shaders/include/fe_gbuffer.glsl:
// an edge pixel shaded per sample, the others once).
#pragma once
#include "render/TechniqueRenderer.h"

namespace fe::render {

struct GBuffer {
    static constexpr gdi::Format kFormat0 = gdi::Format::RGBA8_SRGB,
                                 kFormat1 = gdi::Format::RGBA16F, kFormat2 = gdi::Format::RGBA16F,
                                 kFormat3 = gdi::Format::R16F;
    graph::TextureId gb0, gb1, gb2, gb3, depth;  // gb3: only with occlusion and image-based light
    gdi::TextureHandle noOcclusion;              // bound in gb3's place without it (one sample)
    uint32_t samples = 1;                        // per pixel, in every target and the depth

    // The variant of a lighting pass's shader (registry name) reading this G-buffer under the
    // context's settings: NAME, or NAME:FE_MULTISAMPLED (and +FE_OCCLUSION for the image-based
    // lighting pass's, `occlusion`, when gb3 exists).
    static std::string shader(const TechniqueContext& ctx, const std::string& name,
                              bool occlusion = false);
    // Whether gb3 is made: image-based light and a material with an occlusion texture.
    static bool hasOcclusion(const TechniqueContext& ctx);

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
