// Layer 7: redeferred shading (../shared/seeds/000): G-buffer; an illumination pass into the
// I-buffer (L_dg and the specular sums, at 1/--illum-scale of the resolution per axis): the
// lights drawn as volumes, or (tiled) one compute pass shading per 16x16-pixel tile the lights
// the light-culling pass (TileLightCulling) listed for it;
// a material pass turning the upsampled sums into L_o. With per-source rates (RenderSettings::
// rates) each source (lights, shadowed lights, the environment's diffuse and specular halves)
// adds into the I-buffer of its own rate, and each reduced one is upsampled into the full-rate
// I-buffer the material pass reads.
#pragma once
#include <memory>

#include "render/ShadowedLightVolumes.h"

#include "render/EnvironmentLighting.h"
#include "render/GBuffer.h"
#include "render/LightVolumes.h"
#include "render/TemporalAccumulation.h"
#include "render/TileLightCulling.h"

namespace fe::render {

class RedeferredRenderer final : public TechniqueRenderer {
public:
    RedeferredRenderer(TechniqueContext& context, bool tiled);
    void declare(graph::RenderGraph& graph, graph::TextureId output,
                 graph::TextureId depth) override;
    LightLists lightLists() const override { return {LightLists::Kind::NotMeasured, {}}; }

    // I-buffer: L_dg fits half floats; the alpha^2/(4 pi)-scaled specular sums reach ~2e4 x E at
    // the roughness clamp, beyond half range for bright lights, so they are 32-bit.
    // L_dg is an irradiance: E = I / d^2 passes half-float range (65504) for the lights the engine
    // accepts (the stability suite's 1e7 cd), and NVIDIA's additive blending of half floats
    // then stores infinity where lavapipe saturates (H100, 2026-11-27). All three are 32-bit.
    static constexpr gdi::Format kI0 = gdi::Format::RGBA32F, kI1 = gdi::Format::RGBA32F,
                                 kI2 = gdi::Format::RGBA32F;

private:
    // One I-buffer: L_dg, L_sg1, L_sg2 at 1/rate (the specular sums' size in width, height).
    struct IBuffer {
        uint32_t rate = 1;
        graph::TextureId l0, l1, l2;
        uint32_t width = 0, height = 0;
    };
    IBuffer createIBuffer(graph::RenderGraph& g, uint32_t rate) const;
    // The frame constants of passes at `rate` (its scale and I-buffer size), with per-source
    // rates; otherwise empty (the frame's own).
    FrameConstantsFn frameAtRate(uint32_t rate) const;
    void declarePunctual(graph::RenderGraph& g, const IBuffer& ib);
    void declareShadowed(graph::RenderGraph& g, const IBuffer& ib);

    gdi::DeviceObjects objects_;
    std::unique_ptr<ShadowedLightVolumes> shadowed_;  // with shadows: each shadowed light's pass
    bool tiled_;
    bool perSource_ = false;  // RenderSettings::perSourceRates()
    GBuffer gbuffer_;
    std::unique_ptr<LightVolumes> volumes_;
    std::unique_ptr<TileLightCulling> culling_;  // tiled
    gdi::ShaderHandle illuminationCs_;
    std::unique_ptr<FeatureComputePipelines> illumination_;  // tiled, by the frame's ShaderFeatures
    gdi::ShaderHandle materialFs_;
    gdi::PipelineHandle material_;
    std::unique_ptr<EnvironmentLighting>
        ibl_;  // with IBL: the environment into the I-buffer (or its L_dg alone)
    std::unique_ptr<EnvironmentLighting> iblSpecular_;  // per-source rates apart: its L_sg1, L_sg2
    std::unique_ptr<TemporalAccumulation> temporal_;    // RenderSettings::temporal
    gdi::ShaderHandle upsampleFs_;  // per-source rates: a reduced I-buffer into the full-rate one
    gdi::PipelineHandle upsample_;
};

}  // namespace fe::render
