// Layer 7: redeferred shading (../shared/seeds/000): G-buffer; an illumination pass into the
// I-buffer (L_dg and the specular sums, at 1/--illum-scale of the resolution per axis): the
// lights drawn as volumes, or (tiled) one compute pass shading per 16x16-pixel tile the lights
// the light-culling pass (TileLightCulling) listed for it;
// a material pass turning the upsampled sums into L_o.
#pragma once
#include <memory>

#include "render/ShadowedLightVolumes.h"

#include "render/EnvironmentLighting.h"
#include "render/GBuffer.h"
#include "render/LightVolumes.h"
#include "render/TileLightCulling.h"

namespace fe::render {

class RedeferredRenderer final : public TechniqueRenderer {
public:
    RedeferredRenderer(TechniqueContext& context, bool tiled);
    ~RedeferredRenderer() override;
    void declare(graph::RenderGraph& graph, graph::TextureId output, graph::TextureId depth) override;

    // I-buffer: L_dg fits half floats; the alpha^2/(4 pi)-scaled specular sums reach ~2e4 x E at
    // the roughness clamp, beyond half range for bright lights, so they are 32-bit.
    static constexpr gdi::Format kI0 = gdi::Format::RGBA16F, kI1 = gdi::Format::RGBA32F, kI2 = gdi::Format::RGBA32F;

private:
    std::unique_ptr<ShadowedLightVolumes> shadowed_;  // with shadows: each shadowed light's pass
    bool tiled_;
    GBuffer gbuffer_;
    std::unique_ptr<LightVolumes> volumes_;
    std::unique_ptr<TileLightCulling> culling_;  // tiled
    gdi::ShaderHandle illuminationCs_;
    gdi::PipelineHandle illumination_;  // tiled
    gdi::ShaderHandle materialFs_;
    gdi::PipelineHandle material_;
    std::unique_ptr<EnvironmentLighting> ibl_;  // with --ibl-samples: the environment into the I-buffer
};

}  // namespace fe::render
