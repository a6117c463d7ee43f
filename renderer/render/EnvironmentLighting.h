// Layer 7: image-based lighting for the techniques that shade from a G-buffer (deferred,
// deferred-tiled): one full-screen pass adding each pixel's environment light to L_o
// (shaders/scene/deferred_ibl.frag, the estimator of fe_ibl.glsl). Declared only when the frame
// asks for it (RenderSettings::iblSamples).
#pragma once
#include "render/GBuffer.h"

namespace fe::render {

class EnvironmentLighting {
public:
    explicit EnvironmentLighting(TechniqueContext& context);
    ~EnvironmentLighting();
    EnvironmentLighting(const EnvironmentLighting&) = delete;
    EnvironmentLighting& operator=(const EnvironmentLighting&) = delete;
    // Declares the "ibl" pass after the lighting passes: reads the G-buffer, adds into `output`.
    void declare(graph::RenderGraph& g, const GBuffer& gbuffer, graph::TextureId output);

private:
    TechniqueContext& ctx_;
    gdi::ShaderHandle fs_;
    gdi::PipelineHandle pipeline_;
};

}  // namespace fe::render
