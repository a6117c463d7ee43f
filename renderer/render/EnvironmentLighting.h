// Layer 7: image-based lighting for the techniques that shade from a G-buffer: one full-screen
// pass reading the G-buffer and adding the environment's light into its targets (colour added,
// alpha kept), by the estimator of shaders/include/fe_ibl.glsl. deferred and deferred-tiled add
// L_o (scene/deferred_ibl.frag); redeferred adds the I-buffer sums (scene/illumination_ibl.frag).
// Made only when the frame asks for it (RenderSettings::iblSamples).
#pragma once
#include <vector>

#include "render/GBuffer.h"

namespace fe::render {

class EnvironmentLighting {
public:
    // `albedo`: whether the shader reads G-buffer 0 (base colour and metallic).
    EnvironmentLighting(TechniqueContext& context, const char* fragmentShader,
                        std::vector<gdi::Format> targetFormats, bool albedo);
    EnvironmentLighting(const EnvironmentLighting&) = delete;
    EnvironmentLighting& operator=(const EnvironmentLighting&) = delete;
    // Declares the pass after the lighting passes: reads the G-buffer, adds into `targets`.
    // `frame`: the pass's frame constants (default: the frame's own).
    void declare(graph::RenderGraph& g, const char* passName, const GBuffer& gbuffer,
                 std::vector<graph::TextureId> targets, FrameConstantsFn frame = {});

private:
    gdi::DeviceObjects objects_;
    TechniqueContext& ctx_;
    bool albedo_;
    gdi::ShaderHandle fs_;
    gdi::PipelineHandle pipeline_;
};

}  // namespace fe::render
