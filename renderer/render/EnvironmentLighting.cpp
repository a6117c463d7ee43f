#include "render/EnvironmentLighting.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

EnvironmentLighting::EnvironmentLighting(TechniqueContext& c, const char* fragmentShader,
                                         std::vector<gdi::Format> formats, bool albedo)
    : objects_(c.device), ctx_(c), albedo_(albedo) {
    // The multisampled variant under --msaa (the deferred family; the others refuse --msaa).
    const std::string shader = GBuffer::shader(c, c.environmentLight.shader(fragmentShader), true);
    fs_ = objects_.add(c.device.createShader(
        {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find(shader)}));
    const gdi::BlendTargetState add{.enable = true,
                                    .srcColor = gdi::BlendFactor::One,
                                    .dstColor = gdi::BlendFactor::One,
                                    .srcAlpha = gdi::BlendFactor::Zero,
                                    .dstAlpha = gdi::BlendFactor::One};
    pipeline_ = objects_.add(c.device.createGraphicsPipeline(
        {.vertexShader = c.fullscreenVs,
         .fragmentShader = fs_,
         .blend = std::vector<gdi::BlendTargetState>(formats.size(), add),
         .colorFormats = formats,
         .debugName = fragmentShader}));
}

void EnvironmentLighting::declare(graph::RenderGraph& g, const char* passName,
                                  const GBuffer& gbuffer, std::vector<graph::TextureId> targets,
                                  FrameConstantsFn frame) {
    g.addPass(
        passName,
        [&](graph::PassBuilder& b) {
            gbuffer.sampleIn(b, albedo_);
            gbuffer.sampleOcclusionIn(b);
            for (graph::TextureId t : targets) b.colorTarget(t, gdi::LoadOp::Load);
        },
        [this, &gbuffer, frame](graph::PassContext& pc) {
            pc.beginRenderPass();
            pc.cmd.setPipeline(pipeline_);
            const UploadAllocation fc = frame ? frame() : ctx_.frameConstants;
            pc.cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
            gbuffer.bind(pc.cmd, pc, ctx_.pointSampler, albedo_);
            gbuffer.bindOcclusion(pc.cmd, pc, ctx_.pointSampler);
            ctx_.environmentLight.bind(pc.cmd);
            pc.cmd.draw(3);
            pc.cmd.endRenderPass();
        });
}

}  // namespace fe::render
