// Layer 7 (Render): temporal accumulation of redeferred's reduced-rate illumination (the seed's
// consideration D). Each frame the I-buffer texels sample a different pixel of their block
// (FrameConstants::temporal, set by SceneRenderer from temporalOffset()); a full-resolution
// pass ("temporal-resolve", shaders/scene/temporal_resolve.frag) averages, per pixel, the exact
// sums of the frames on which it was sampled, reprojected from last frame's history and
// rejected by depth; a second pass keeps the result as next frame's history. The material pass
// then resolves the accumulated sums at full rate. A still view converges to the full-rate
// image after scale^2 frames; a moving one degrades to the spatial upsampling where history is
// lost (disocclusions) and carries stale view-dependent sums elsewhere (measured).
#pragma once
#include <array>

#include "render/GBuffer.h"
#include "render/TechniqueRenderer.h"

namespace fe::render {

// The representative pixel's offset within a scale x scale block on frame `frame`: a Bayer
// (ordered dither) sequence, so any scale^2 consecutive frames visit every pixel of the block
// and any few of them spread over it.
glm::uvec2 temporalOffset(uint32_t scale, uint64_t frame);

class TemporalAccumulation {
public:
    static constexpr gdi::Format kFormat = gdi::Format::RGBA32F;
    static constexpr float kMaxFrames =
        8.0f;  // history cap under motion (FrameConstants::temporal.w)

    explicit TemporalAccumulation(TechniqueContext& context);
    TemporalAccumulation(const TemporalAccumulation&) = delete;
    TemporalAccumulation& operator=(const TemporalAccumulation&) = delete;

    // Declares the resolve and history passes after the illumination passes filled `ibuffer`;
    // returns the accumulated full-resolution sums (L_dg, L_sg1, L_sg2) for the material pass.
    std::array<graph::TextureId, 3> declare(graph::RenderGraph& g, const GBuffer& gbuffer,
                                            const std::array<graph::TextureId, 3>& ibuffer);

private:
    gdi::DeviceObjects objects_;
    TechniqueContext& ctx_;
    std::array<gdi::TextureHandle, 3> history_;
    gdi::SamplerHandle linear_;
    gdi::ShaderHandle resolveFs_, keepFs_;
    gdi::PipelineHandle resolve_, keep_;
};

}  // namespace fe::render
