#include "render/DeferredRenderer.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

DeferredRenderer::DeferredRenderer(TechniqueContext& c) : TechniqueRenderer(c), objects_(c.device) {
    volumes_ = std::make_unique<LightVolumes>(
        c.device, GBuffer::shader(c, "scene/deferred_light.frag"), std::vector{kRadianceFormat});
    emissiveFs_ = objects_.add(c.device.createShader(
        {.stage = gdi::ShaderStage::Fragment,
         .binary = shaders::find(GBuffer::shader(c, "scene/emissive.frag"))}));
    emissive_ = objects_.add(
        c.device.createGraphicsPipeline({.vertexShader = c.fullscreenVs,
                                         .fragmentShader = emissiveFs_,
                                         .blend = {{.enable = true,
                                                    .srcColor = gdi::BlendFactor::One,
                                                    .dstColor = gdi::BlendFactor::One,
                                                    .srcAlpha = gdi::BlendFactor::One,
                                                    .dstAlpha = gdi::BlendFactor::One}},
                                         .colorFormats = {kRadianceFormat},
                                         .debugName = "emissive"}));
    if (c.shadows)
        shadowed_ = std::make_unique<ShadowedLightVolumes>(
            c, GBuffer::shader(c, "scene/deferred_light_shadowed.frag"),
            GBuffer::shader(c, "scene/deferred_light_shadowed_cube.frag"),
            std::vector{kRadianceFormat});
    if (c.settings.ibl())
        ibl_ = std::make_unique<EnvironmentLighting>(c, "scene/deferred_ibl.frag",
                                                     std::vector{kRadianceFormat}, true);
}

void DeferredRenderer::declare(graph::RenderGraph& g, graph::TextureId output,
                               graph::TextureId depth) {
    gbuffer_.declare(g, ctx_, depth);
    g.addPass(
        "lighting",
        [&](graph::PassBuilder& b) {
            gbuffer_.sampleIn(b, true);
            b.colorTarget(output);
        },
        [this](graph::PassContext& pc) {
            pc.beginRenderPass();
            gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, true);
            volumes_->draw(pc.cmd, ctx_.queue, ctx_.scene, ctx_.frameConstants, ctx_.frame);
            pc.cmd.endRenderPass();
        });
    if (shadowed_)
        shadowed_->declare(
            g,
            [&](graph::PassBuilder& b) {
                gbuffer_.sampleIn(b, true);
                b.colorTarget(output, gdi::LoadOp::Load);
            },
            [this](graph::PassContext& pc) { gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, true); });
    g.addPass(
        "emissive",
        [&](graph::PassBuilder& b) {
            b.sample(gbuffer_.gb2);
            b.colorTarget(output, gdi::LoadOp::Load);
        },
        fullscreen(emissive_, {{kSlotGBuffer2, gbuffer_.gb2}}));
    if (ibl_) ibl_->declare(g, "ibl", gbuffer_, {output});
}

}  // namespace fe::render
