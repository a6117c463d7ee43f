// Layer 7: deferred shading: G-buffer, then every light drawn as a volume (sphere, cone or
// full-screen triangle) over it, accumulated additively into L_o, then the emissive term.
#pragma once
#include <memory>

#include "render/ShadowedLightVolumes.h"

#include "render/EnvironmentLighting.h"
#include "render/GBuffer.h"
#include "render/LightVolumes.h"

namespace fe::render {

class DeferredRenderer final : public TechniqueRenderer {
public:
    explicit DeferredRenderer(TechniqueContext& context);
    void declare(graph::RenderGraph& graph, graph::TextureId output,
                 graph::TextureId depth) override;
    LightLists lightLists() const override { return {LightLists::Kind::NotMeasured, {}}; }

private:
    gdi::DeviceObjects objects_;
    std::unique_ptr<ShadowedLightVolumes> shadowed_;  // with shadows: each shadowed light's pass
    GBuffer gbuffer_;
    std::unique_ptr<EnvironmentLighting> ibl_;  // with --ibl-samples
    std::unique_ptr<LightVolumes> volumes_;
    gdi::ShaderHandle emissiveFs_;
    gdi::PipelineHandle emissive_;
};

}  // namespace fe::render
