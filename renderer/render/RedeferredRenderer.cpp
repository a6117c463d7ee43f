#include "render/RedeferredRenderer.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

RedeferredRenderer::RedeferredRenderer(TechniqueContext& c, bool tiled) : TechniqueRenderer(c), tiled_(tiled) {
    if (c.settings.illumSplit && c.settings.illumScale == 1)
        throw gdi::Error("--illum-split needs --illum-scale 2 or 4 (at full rate nothing is upsampled)");
    if (tiled) {
        if (!c.device.info().features.computeShaders)
            throw gdi::Error("technique redeferred-tiled needs compute shaders, which " + c.device.info().backend + " lacks");
        // One shader per scale: a tile is 16x16 pixels, 16 / scale texels wide (the split
        // I-buffer is written per pixel at every scale).
        const char* shader = c.settings.illumSplit         ? "scene/tiled_illumination_split.comp"
                             : c.settings.illumScale == 4 ? "scene/tiled_illumination_s4.comp"
                             : c.settings.illumScale == 2 ? "scene/tiled_illumination_s2.comp"
                                                          : "scene/tiled_illumination.comp";
        illuminationCs_ = c.device.createShader({.stage = gdi::ShaderStage::Compute, .binary = shaders::find(shader)});
        culling_ = std::make_unique<TileLightCulling>(c);
        std::vector<gdi::BindingSlot> b = GBuffer::computeSlots(false);
        b.push_back(TileLightCulling::listSlot());
        for (uint32_t slot : {kSlotIBuffer0, kSlotIBuffer1, kSlotIBuffer2})
            b.push_back({slot, gdi::BindingType::StorageTexture, gdi::ShaderStage::Compute});
        illumination_ = c.device.createComputePipeline({.computeShader = illuminationCs_, .bindings = b,
                                                        .debugName = "tiled illumination"});
    } else {
        // The volume pass writes the three sums as one multiple-render-target draw, so they
        // must have one size.
        if (c.settings.illumSplit)
            throw gdi::Error("--illum-split needs technique redeferred-tiled (redeferred draws all I-buffer sums at one size)");
        volumes_ = std::make_unique<LightVolumes>(c.device, "scene/illumination.frag", std::vector{kI0, kI1, kI2},
                                                  GBuffer::slots(false));
    }
    const RenderSettings& s = c.settings;
    if (c.shadows) {
        if (s.illumSplit)
            throw gdi::Error("--illum-split does not take shadows yet (its I-buffer sums differ in size)");
        shadowed_ = std::make_unique<ShadowedLightVolumes>(c, "scene/illumination_shadowed.frag",
                                                           "scene/illumination_shadowed_cube.frag", std::vector{kI0, kI1, kI2},
                                                           GBuffer::slots(false));
    }
    if (s.ibl()) {
        if (s.illumSplit)
            throw gdi::Error("--illum-split does not take image-based lighting yet (its I-buffer sums differ in size)");
        // The environment's light added into the I-buffer (alpha, the tiled pass's filter data, kept).
        ibl_ = std::make_unique<EnvironmentLighting>(c, "scene/illumination_ibl.frag", std::vector{kI0, kI1, kI2}, false);
    }
    // One material shader per path (fe_material_pass.glsl says why).
    const char* material = s.illumScale == 1 ? (s.precomputedNoV ? "scene/material.frag" : "scene/material_rebuild_nov.frag")
                           : s.illumSplit     ? "scene/material_upsample_split.frag"
                           : tiled            ? "scene/material_upsample_tiled.frag"
                                              : "scene/material_upsample.frag";
    materialFs_ = c.device.createShader({.stage = gdi::ShaderStage::Fragment, .binary = shaders::find(material)});
    std::vector<gdi::BindingSlot> b = GBuffer::slots(true);
    b.push_back({kSlotFrame, gdi::BindingType::UniformBuffer, gdi::ShaderStage::AllGraphics});
    for (uint32_t slot : {kSlotIBuffer0, kSlotIBuffer1, kSlotIBuffer2})
        b.push_back({slot, gdi::BindingType::SampledTexture, gdi::ShaderStage::Fragment});
    material_ = c.device.createGraphicsPipeline({.vertexShader = c.fullscreenVs, .fragmentShader = materialFs_,
                                                 .colorFormats = {kRadianceFormat}, .bindings = b, .debugName = "material"});
}

RedeferredRenderer::~RedeferredRenderer() {
    for (auto p : {material_, illumination_}) ctx_.device.destroy(p);
    for (auto sh : {materialFs_, illuminationCs_}) ctx_.device.destroy(sh);
}

void RedeferredRenderer::declare(graph::RenderGraph& g, graph::TextureId output, graph::TextureId depth) {
    gbuffer_.declare(g, ctx_, depth);
    const RenderSettings& s = ctx_.settings;
    const uint32_t iw = (s.width + s.illumScale - 1) / s.illumScale, ih = (s.height + s.illumScale - 1) / s.illumScale;
    const graph::TextureId i0 = g.createTexture("ibuffer0 L_dg", {.format = kI0, .width = iw, .height = ih});
    // Split: the specular sums at full resolution, only L_dg reduced.
    const uint32_t sw = s.illumSplit ? s.width : iw, sh = s.illumSplit ? s.height : ih;
    const graph::TextureId i1 = g.createTexture("ibuffer1 L_sg1", {.format = kI1, .width = sw, .height = sh});
    const graph::TextureId i2 = g.createTexture("ibuffer2 L_sg2", {.format = kI2, .width = sw, .height = sh});
    if (tiled_) {
        const graph::TextureId lists = culling_->declare(g, gbuffer_.depth);
        g.addPass("tiled-illumination", [&](graph::PassBuilder& b) {
            gbuffer_.sampleIn(b, false);
            b.sample(lists);
            for (auto t : {i0, i1, i2}) b.storage(t);
        }, [this, i0, i1, i2, sw, sh, lists](graph::PassContext& pc) {
            bindFrameAndLights(pc.cmd, illumination_);
            gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, false);
            culling_->bindLists(pc.cmd, pc, lists);
            pc.cmd.setStorageTexture(kSlotIBuffer0, pc.texture(i0));
            pc.cmd.setStorageTexture(kSlotIBuffer1, pc.texture(i1));
            pc.cmd.setStorageTexture(kSlotIBuffer2, pc.texture(i2));
            // One work group per 16x16-pixel tile; (sw, sh) are the specular sums' texels.
            const uint32_t texels = ctx_.settings.illumSplit ? 16 : 16 / ctx_.settings.illumScale;
            pc.cmd.dispatch((sw + texels - 1) / texels, (sh + texels - 1) / texels);
        });
    } else {
        g.addPass("illumination", [&](graph::PassBuilder& b) {
            gbuffer_.sampleIn(b, false);
            for (auto t : {i0, i1, i2}) b.colorTarget(t);
        }, [this](graph::PassContext& pc) {
            pc.beginRenderPass();
            gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, false);
            volumes_->draw(pc.cmd, ctx_.queue, ctx_.scene, ctx_.frameConstants);
            pc.cmd.endRenderPass();
        });
    }
    if (shadowed_)
        shadowed_->declare(g, [&](graph::PassBuilder& b) {
            gbuffer_.sampleIn(b, false);
            for (auto t : {i0, i1, i2}) b.colorTarget(t, gdi::LoadOp::Load);
        }, [this](graph::PassContext& pc) { gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, false); });
    if (ibl_) ibl_->declare(g, "ibl-illumination", gbuffer_, {i0, i1, i2});
    g.addPass("material", [&](graph::PassBuilder& b) {
        gbuffer_.sampleIn(b, true);
        for (auto t : {i0, i1, i2}) b.sample(t);
        b.colorTarget(output);
    }, fullscreen(material_, {{kSlotGBuffer0, gbuffer_.gb0}, {kSlotGBuffer1, gbuffer_.gb1}, {kSlotGBuffer2, gbuffer_.gb2},
                              {kSlotDepth, gbuffer_.depth}, {kSlotIBuffer0, i0}, {kSlotIBuffer1, i1}, {kSlotIBuffer2, i2}}));
}

}  // namespace fe::render
