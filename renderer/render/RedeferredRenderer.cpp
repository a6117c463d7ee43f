#include "render/RedeferredRenderer.h"

#include <map>

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

RedeferredRenderer::RedeferredRenderer(TechniqueContext& c, bool tiled)
    : TechniqueRenderer(c), objects_(c.device), tiled_(tiled) {
    const RenderSettings& s = c.settings;
    perSource_ = s.perSourceRates();
    if (s.illumSplit && s.illumScale == 1)
        throw gdi::Error(
            "--illum-split needs --illum-scale 2 or 4 (at full rate nothing is upsampled)");
    // The punctual lights' rate: the I-buffer's, or their own with per-source rates.
    const uint32_t punctual = perSource_ ? s.rate(s.rates.punctual) : s.illumScale;
    if (tiled) {
        if (!c.device.info().features.computeShaders)
            throw gdi::Error("technique redeferred-tiled needs compute shaders, which " +
                             c.device.info().backend + " lacks");
        // One shader per scale: a tile is 16x16 pixels, 16 / scale texels wide (the split
        // I-buffer is written per pixel at every scale).
        const char* shader = s.illumSplit    ? "tiled_illumination_split"
                             : punctual == 4 ? "tiled_illumination_s4"
                             : punctual == 2 ? "tiled_illumination_s2"
                                             : "tiled_illumination";
        culling_ = std::make_unique<TileLightCulling>(c);
        illuminationCs_ = objects_.add(c.device.createShader(
            {.stage = gdi::ShaderStage::Compute, .binary = culling_->shader(shader)}));
        illumination_ = std::make_unique<FeatureComputePipelines>(c.device, illuminationCs_,
                                                                  "tiled illumination");
    } else {
        // The volume pass writes the three sums as one multiple-render-target draw, so they
        // must have one size.
        if (s.illumSplit)
            throw gdi::Error(
                "--illum-split needs technique redeferred-tiled (redeferred draws all I-buffer sums at one size)");
        volumes_ = std::make_unique<LightVolumes>(c.device, "scene/illumination.frag",
                                                  std::vector{kI0, kI1, kI2});
    }
    if (c.shadows) {
        if (s.illumSplit)
            throw gdi::Error(
                "--illum-split does not take shadows yet (its I-buffer sums differ in size)");
        shadowed_ = std::make_unique<ShadowedLightVolumes>(c, "scene/illumination_shadowed.frag",
                                                           "scene/illumination_shadowed_cube.frag",
                                                           std::vector{kI0, kI1, kI2});
    }
    if (s.ibl()) {
        if (s.illumSplit)
            throw gdi::Error(
                "--illum-split does not take image-based lighting yet (its I-buffer sums differ in size)");
        // The environment's light added into the I-buffer (alpha, the tiled pass's filter data, kept):
        // both halves in one pass, or with per-source rates each half into its own rate's I-buffer.
        if (perSource_ && s.rate(s.rates.iblDiffuse) != s.rate(s.rates.iblSpecular)) {
            ibl_ = std::make_unique<EnvironmentLighting>(c, "scene/illumination_ibl_diffuse.frag",
                                                         std::vector{kI0}, false);
            iblSpecular_ = std::make_unique<EnvironmentLighting>(
                c, "scene/illumination_ibl_specular.frag", std::vector{kI1, kI2}, false);
        } else {
            ibl_ = std::make_unique<EnvironmentLighting>(c, "scene/illumination_ibl.frag",
                                                         std::vector{kI0, kI1, kI2}, false);
        }
    }
    if (s.temporal) {
        if (s.illumScale == 1)
            throw gdi::Error(
                "--temporal needs --illum-scale 2 or 4 (at full rate there is nothing to accumulate)");
        if (perSource_ || s.illumSplit)
            throw gdi::Error(
                "--temporal takes one illumination rate (not --rates or --illum-split)");
        temporal_ = std::make_unique<TemporalAccumulation>(c);
    }
    if (perSource_) {
        upsampleFs_ = objects_.add(
            c.device.createShader({.stage = gdi::ShaderStage::Fragment,
                                   .binary = shaders::find("scene/ibuffer_upsample.frag")}));
        const gdi::BlendTargetState add{.enable = true,
                                        .srcColor = gdi::BlendFactor::One,
                                        .dstColor = gdi::BlendFactor::One,
                                        .srcAlpha = gdi::BlendFactor::Zero,
                                        .dstAlpha = gdi::BlendFactor::One};
        upsample_ =
            objects_.add(c.device.createGraphicsPipeline({.vertexShader = c.fullscreenVs,
                                                          .fragmentShader = upsampleFs_,
                                                          .blend = {add, add, add},
                                                          .colorFormats = {kI0, kI1, kI2},
                                                          .debugName = "I-buffer upsample"}));
    }
    // One material shader per path (fe_material_pass.glsl says why). Per-source rates resolve the
    // full-rate I-buffer the reduced ones were added into.
    const uint32_t scale = perSource_ || temporal_ ? 1 : s.illumScale;
    const char* material =
        scale == 1 ? (s.precomputedNoV ? "scene/material.frag" : "scene/material_rebuild_nov.frag")
        : s.illumSplit ? "scene/material_upsample_split.frag"
        : tiled        ? "scene/material_upsample_tiled.frag"
                       : "scene/material_upsample.frag";
    materialFs_ = objects_.add(c.device.createShader(
        {.stage = gdi::ShaderStage::Fragment, .binary = shaders::find(material)}));
    material_ = objects_.add(c.device.createGraphicsPipeline({.vertexShader = c.fullscreenVs,
                                                              .fragmentShader = materialFs_,
                                                              .colorFormats = {kRadianceFormat},
                                                              .debugName = "material"}));
}

RedeferredRenderer::IBuffer RedeferredRenderer::createIBuffer(graph::RenderGraph& g,
                                                              uint32_t rate) const {
    const RenderSettings& s = ctx_.settings;
    const uint32_t iw = (s.width + rate - 1) / rate, ih = (s.height + rate - 1) / rate;
    const std::string suffix = perSource_ ? " 1/" + std::to_string(rate) : "";
    // Split: the specular sums at full resolution, only L_dg reduced.
    const uint32_t sw = s.illumSplit ? s.width : iw, sh = s.illumSplit ? s.height : ih;
    return {rate,
            g.createTexture("ibuffer0 L_dg" + suffix, {.format = kI0, .width = iw, .height = ih}),
            g.createTexture("ibuffer1 L_sg1" + suffix, {.format = kI1, .width = sw, .height = sh}),
            g.createTexture("ibuffer2 L_sg2" + suffix, {.format = kI2, .width = sw, .height = sh}),
            sw,
            sh};
}

FrameConstantsFn RedeferredRenderer::frameAtRate(uint32_t rate) const {
    if (!perSource_) return {};
    return [this, rate]() {
        const RenderSettings& s = ctx_.settings;
        const uint32_t iw = (s.width + rate - 1) / rate, ih = (s.height + rate - 1) / rate;
        FrameConstants fc = ctx_.frame;
        fc.counts.y = rate;
        fc.illumViewport = glm::vec4(iw, ih, 1.0f / iw, 1.0f / ih);
        fc.temporal.x = fc.temporal.y = float(rate / 2);
        return ctx_.queue.upload(fc);
    };
}

void RedeferredRenderer::declarePunctual(graph::RenderGraph& g, const IBuffer& ib) {
    const FrameConstantsFn frame = frameAtRate(ib.rate);
    if (tiled_) {
        const graph::TextureId lists = culling_->declare(g, gbuffer_.depth);
        g.addPass(
            "tiled-illumination",
            [&](graph::PassBuilder& b) {
                gbuffer_.sampleIn(b, false);
                b.sample(lists);
                for (auto t : {ib.l0, ib.l1, ib.l2}) b.storage(t);
            },
            [this, ib, lists, frame](graph::PassContext& pc) {
                culling_->bindFrameAndLights(pc.cmd, (*illumination_)(frameFeatures(ctx_)));
                if (frame) {
                    const UploadAllocation fc = frame();
                    pc.cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
                }
                gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, false);
                culling_->bindLists(pc.cmd, pc, lists);
                pc.cmd.setStorageTexture(kSlotIBuffer0, pc.texture(ib.l0));
                pc.cmd.setStorageTexture(kSlotIBuffer1, pc.texture(ib.l1));
                pc.cmd.setStorageTexture(kSlotIBuffer2, pc.texture(ib.l2));
                // One work group per 16x16-pixel tile; (width, height) are the specular sums' texels.
                const uint32_t texels = ctx_.settings.illumSplit ? 16 : 16 / ib.rate;
                pc.cmd.dispatch((ib.width + texels - 1) / texels,
                                (ib.height + texels - 1) / texels);
            });
    } else {
        g.addPass(
            "illumination",
            [&](graph::PassBuilder& b) {
                gbuffer_.sampleIn(b, false);
                for (auto t : {ib.l0, ib.l1, ib.l2}) b.colorTarget(t);
            },
            [this, frame](graph::PassContext& pc) {
                pc.beginRenderPass();
                gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, false);
                volumes_->draw(pc.cmd, ctx_.queue, ctx_.scene,
                               frame ? frame() : ctx_.frameConstants, ctx_.frame);
                pc.cmd.endRenderPass();
            });
    }
}

void RedeferredRenderer::declareShadowed(graph::RenderGraph& g, const IBuffer& ib) {
    if (!shadowed_) return;
    shadowed_->declare(
        g,
        [&](graph::PassBuilder& b) {
            gbuffer_.sampleIn(b, false);
            for (auto t : {ib.l0, ib.l1, ib.l2}) b.colorTarget(t, gdi::LoadOp::Load);
        },
        [this](graph::PassContext& pc) { gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, false); },
        frameAtRate(ib.rate));
}

void RedeferredRenderer::declare(graph::RenderGraph& g, graph::TextureId output,
                                 graph::TextureId depth) {
    gbuffer_.declare(g, ctx_, depth);
    const RenderSettings& s = ctx_.settings;
    IBuffer full;
    if (!perSource_) {
        full = createIBuffer(g, s.illumScale);
        declarePunctual(g, full);
        declareShadowed(g, full);
        if (ibl_) ibl_->declare(g, "ibl-illumination", gbuffer_, {full.l0, full.l1, full.l2});
        if (temporal_) {  // the material pass resolves the accumulated full-resolution sums
            const auto acc = temporal_->declare(g, gbuffer_, {full.l0, full.l1, full.l2});
            full = {1, acc[0], acc[1], acc[2], s.width, s.height};
        }
    } else {
        // Each source into the I-buffer of its rate; every reduced one then upsampled, with the
        // G-buffer-guided filter, into the full-rate one the material pass reads.
        std::map<uint32_t, IBuffer> buffers;
        auto at = [&](uint32_t rate) -> const IBuffer& {
            auto it = buffers.find(rate);
            if (it != buffers.end()) return it->second;
            const IBuffer ib = createIBuffer(g, rate);
            // Cleared first: the sources load what is there (a pass that overwrites it all, the
            // tiled illumination, lets the graph cull this).
            g.addPass(
                "clear I-buffer 1/" + std::to_string(rate),
                [&](graph::PassBuilder& b) {
                    for (auto t : {ib.l0, ib.l1, ib.l2}) b.colorTarget(t);
                },
                [](graph::PassContext& pc) {
                    pc.beginRenderPass();
                    pc.cmd.endRenderPass();
                });
            return buffers.emplace(rate, ib).first->second;
        };
        full = at(1);
        declarePunctual(g, at(s.rate(s.rates.punctual)));
        if (shadowed_) declareShadowed(g, at(s.rate(s.rates.shadowed)));
        if (ibl_ && !iblSpecular_) {
            const IBuffer& ib = at(s.rate(s.rates.iblDiffuse));
            ibl_->declare(g, "ibl-illumination", gbuffer_, {ib.l0, ib.l1, ib.l2},
                          frameAtRate(ib.rate));
        } else if (ibl_) {
            const IBuffer& d = at(s.rate(s.rates.iblDiffuse));
            ibl_->declare(g, "ibl-diffuse", gbuffer_, {d.l0}, frameAtRate(d.rate));
            const IBuffer& sp = at(s.rate(s.rates.iblSpecular));
            iblSpecular_->declare(g, "ibl-specular", gbuffer_, {sp.l1, sp.l2},
                                  frameAtRate(sp.rate));
        }
        for (const auto& entry :
             buffers) {  // not a structured binding: lambdas capture `ib` (clang 14)
            const uint32_t rate = entry.first;
            const IBuffer& ib = entry.second;
            if (rate == 1) continue;
            g.addPass(
                "upsample I-buffer 1/" + std::to_string(rate),
                [&](graph::PassBuilder& b) {
                    gbuffer_.sampleIn(b, false);
                    for (auto t : {ib.l0, ib.l1, ib.l2}) b.sample(t);
                    for (auto t : {full.l0, full.l1, full.l2}) b.colorTarget(t, gdi::LoadOp::Load);
                },
                [this, ib, frame = frameAtRate(rate)](graph::PassContext& pc) {
                    pc.beginRenderPass();
                    pc.cmd.setPipeline(upsample_);
                    const UploadAllocation fc = frame();
                    pc.cmd.setUniformBuffer(kSlotFrame, fc.buffer, fc.offset, fc.size);
                    gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, false);
                    pc.cmd.setTexture(kSlotIBuffer0, pc.texture(ib.l0), ctx_.pointSampler);
                    pc.cmd.setTexture(kSlotIBuffer1, pc.texture(ib.l1), ctx_.pointSampler);
                    pc.cmd.setTexture(kSlotIBuffer2, pc.texture(ib.l2), ctx_.pointSampler);
                    pc.cmd.draw(3);
                    pc.cmd.endRenderPass();
                });
        }
    }
    g.addPass(
        "material",
        [&](graph::PassBuilder& b) {
            gbuffer_.sampleIn(b, true);
            for (auto t : {full.l0, full.l1, full.l2}) b.sample(t);
            b.colorTarget(output);
        },
        fullscreen(material_, {{kSlotGBuffer0, gbuffer_.gb0},
                               {kSlotGBuffer1, gbuffer_.gb1},
                               {kSlotGBuffer2, gbuffer_.gb2},
                               {kSlotDepth, gbuffer_.depth},
                               {kSlotIBuffer0, full.l0},
                               {kSlotIBuffer1, full.l1},
                               {kSlotIBuffer2, full.l2}}));
}

}  // namespace fe::render
