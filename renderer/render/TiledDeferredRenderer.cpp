#include "render/TiledDeferredRenderer.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ShaderSlots.h"

namespace fe::render {

TiledDeferredRenderer::TiledDeferredRenderer(TechniqueContext& c) : TechniqueRenderer(c), objects_(c.device) {
    if (!c.device.info().features.computeShaders)
        throw gdi::Error("technique deferred-tiled needs compute shaders, which " + c.device.info().backend + " lacks");
    if (c.settings.tileCullingPass) culling_ = std::make_unique<TileLightCulling>(c);
    cs_ = objects_.add(c.device.createShader({.stage = gdi::ShaderStage::Compute,
                                              .binary = culling_ ? culling_->shader("tiled_deferred")
                                                                 : shaders::find("scene/tiled_deferred_onepass.comp")}));
    pipeline_ = objects_.add(c.device.createComputePipeline({.computeShader = cs_, .debugName = "tiled lighting"}));
    if (c.shadows)
        shadowed_ = std::make_unique<ShadowedLightVolumes>(c, "scene/deferred_light_shadowed.frag",
                                                           "scene/deferred_light_shadowed_cube.frag",
                                                           std::vector{kRadianceFormat});
    if (c.settings.ibl()) ibl_ = std::make_unique<EnvironmentLighting>(c, "scene/deferred_ibl.frag", std::vector{kRadianceFormat}, true);
}

void TiledDeferredRenderer::declare(graph::RenderGraph& g, graph::TextureId output, graph::TextureId depth) {
    gbuffer_.declare(g, ctx_, depth);
    const graph::TextureId lists = culling_ ? culling_->declare(g, depth) : graph::TextureId{};
    g.addPass("tiled-lighting", [&](graph::PassBuilder& b) {
        gbuffer_.sampleIn(b, true);
        if (culling_) b.sample(lists);
        b.storage(output);
    }, [this, output, lists](graph::PassContext& pc) {
        if (culling_) culling_->bindFrameAndLights(pc.cmd, pipeline_);
        else bindFrameAndLights(pc.cmd, pipeline_);
        gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, true);
        if (culling_) culling_->bindLists(pc.cmd, pc, lists);
        pc.cmd.setStorageTexture(kSlotRadianceOut, pc.texture(output));
        const RenderSettings& s = ctx_.settings;
        pc.cmd.dispatch((s.width + kTileSize - 1) / kTileSize, (s.height + kTileSize - 1) / kTileSize);
    });
    if (shadowed_)
        shadowed_->declare(g, [&](graph::PassBuilder& b) {
            gbuffer_.sampleIn(b, true);
            b.colorTarget(output, gdi::LoadOp::Load);
        }, [this](graph::PassContext& pc) { gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, true); });
    if (ibl_) ibl_->declare(g, "ibl", gbuffer_, {output});
}

}  // namespace fe::render
