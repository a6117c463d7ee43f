#include "render/RedeferredRenderer.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

RedeferredRenderer::RedeferredRenderer(TechniqueContext& c) : TechniqueRenderer(c) {
    volumes_ = std::make_unique<LightVolumes>(c.device, "scene/illumination.frag", std::vector{kI0, kI1, kI2},
                                              GBuffer::slots(false));
    materialFs_ = c.device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find("scene/material.frag")});
    std::vector<gdi::BindingSlot> b = GBuffer::slots(true);
    b.push_back({kSlotFrame, gdi::BindingType::UniformBuffer, gdi::ShaderStage::AllGraphics});
    for (uint32_t slot : {kSlotIBuffer0, kSlotIBuffer1, kSlotIBuffer2})
        b.push_back({slot, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment});
    material_ = c.device.createGraphicsPipeline({.vertexShader = c.fullscreenVs, .fragmentShader = materialFs_,
                                                 .colorFormats = {kRadianceFormat}, .bindings = b, .debugName = "material"});
}

RedeferredRenderer::~RedeferredRenderer() {
    ctx_.device.destroy(material_);
    ctx_.device.destroy(materialFs_);
}

void RedeferredRenderer::declare(graph::RenderGraph& g, graph::TextureId output, graph::TextureId depth) {
    gbuffer_.declare(g, ctx_, depth);
    const RenderSettings& s = ctx_.settings;
    const uint32_t iw = (s.width + s.illumScale - 1) / s.illumScale, ih = (s.height + s.illumScale - 1) / s.illumScale;
    const graph::TextureId i0 = g.createTexture("ibuffer0 L_dg", {.format = kI0, .width = iw, .height = ih});
    const graph::TextureId i1 = g.createTexture("ibuffer1 L_sg1", {.format = kI1, .width = iw, .height = ih});
    const graph::TextureId i2 = g.createTexture("ibuffer2 L_sg2", {.format = kI2, .width = iw, .height = ih});
    g.addPass("illumination", [&](graph::PassBuilder& b) {
        gbuffer_.sampleIn(b, false);
        for (auto t : {i0, i1, i2}) b.colorTarget(t);
    }, [this](graph::PassContext& pc) {
        pc.beginRenderPass();
        gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, false);
        volumes_->draw(pc.cmd, ctx_.queue, ctx_.scene, ctx_.frameConstants);
        pc.cmd.endRenderPass();
    });
    g.addPass("material", [&](graph::PassBuilder& b) {
        gbuffer_.sampleIn(b, true);
        for (auto t : {i0, i1, i2}) b.sample(t);
        b.colorTarget(output);
    }, fullscreen(material_, {{kSlotGBuffer0, gbuffer_.gb0}, {kSlotGBuffer1, gbuffer_.gb1}, {kSlotGBuffer2, gbuffer_.gb2},
                              {kSlotDepth, gbuffer_.depth}, {kSlotIBuffer0, i0}, {kSlotIBuffer1, i1}, {kSlotIBuffer2, i2}}));
}

}  // namespace fe::render
