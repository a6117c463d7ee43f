#include "render/EnvironmentLighting.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

EnvironmentLighting::EnvironmentLighting(TechniqueContext& c) : ctx_(c) {
    fs_ = c.device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/deferred_ibl.frag")});
    std::vector<gdi::BindingSlot> b = GBuffer::slots(true);
    b.push_back({kSlotFrame, gdi::BindingType::UniformBuffer, gdi::ShaderStage::AllGraphics});
    b.push_back({kSlotEnvironment, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment});
    pipeline_ = c.device.createGraphicsPipeline({
        .vertexShader = c.fullscreenVs, .fragmentShader = fs_,
        .blend = {{.enable = true, .srcColor = gdi::BlendFactor::One, .dstColor = gdi::BlendFactor::One,
                   .srcAlpha = gdi::BlendFactor::Zero, .dstAlpha = gdi::BlendFactor::One}},
        .colorFormats = {kRadianceFormat}, .bindings = b, .debugName = "ibl"});
}

EnvironmentLighting::~EnvironmentLighting() {
    ctx_.device.destroy(pipeline_);
    ctx_.device.destroy(fs_);
}

void EnvironmentLighting::declare(graph::RenderGraph& g, const GBuffer& gbuffer, graph::TextureId output) {
    g.addPass("ibl", [&](graph::PassBuilder& b) {
        gbuffer.sampleIn(b, true);
        b.colorTarget(output, gdi::LoadOp::Load);
    }, [this, &gbuffer](graph::PassContext& pc) {
        pc.beginRenderPass();
        pc.cmd.setPipeline(pipeline_);
        const UploadAllocation& fc = ctx_.frameConstants;
        pc.cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
        gbuffer.bind(pc.cmd, pc, ctx_.pointSampler, true);
        pc.cmd.setTexture(kSlotEnvironment, ctx_.environment, ctx_.environmentSampler);
        pc.cmd.draw(3);
        pc.cmd.endRenderPass();
    });
}

}  // namespace fe::render
