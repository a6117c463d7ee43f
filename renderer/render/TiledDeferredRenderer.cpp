#include "render/TiledDeferredRenderer.h"

#include "fe/gdi/ShaderRegistry.h"
#include "render/ClusterLightGrid.h"
#include "render/ShaderSlots.h"

namespace fe::render {

TiledDeferredRenderer::TiledDeferredRenderer(TechniqueContext& c, Lists lists)
    : TechniqueRenderer(c), objects_(c.device), clusters_(lists == Lists::Clusters) {
    if (!c.device.info().features.computeShaders)
        throw gdi::Error(std::string("technique ") +
                         (clusters_ ? "clustered-deferred" : "deferred-tiled") +
                         " needs compute shaders, which " + c.device.info().backend + " lacks");
    if (clusters_ && !c.clusters)
        throw gdi::Error("clustered-deferred: the renderer made no light cluster grid");
    // Under --msaa the lists come from the culling pass, which bounds tiles by every sample's
    // depth (the one-pass form culls for one depth per invocation).
    const bool multisampled = c.settings.msaa > 1;
    if (!clusters_ && (c.settings.tileCullingPass || multisampled))
        culling_ = std::make_unique<TileLightCulling>(c, multisampled);
    const gdi::ShaderBinary& binary =
        clusters_  ? TileLightCulling::listPassShader("clustered_deferred",
                                                      TileLightCulling::lightsFitUniformBlock(c),
                                                      false, multisampled)
        : culling_ ? culling_->shader("tiled_deferred")
                   : shaders::find("scene/tiled_deferred_onepass.comp");
    cs_ =
        objects_.add(c.device.createShader({.stage = gdi::ShaderStage::Compute, .binary = binary}));
    pipelines_ = std::make_unique<FeatureComputePipelines>(c.device, cs_, "tiled lighting");
    if (c.shadows)
        shadowed_ = std::make_unique<ShadowedLightVolumes>(
            c, GBuffer::shader(c, "scene/deferred_light_shadowed.frag"),
            GBuffer::shader(c, "scene/deferred_light_shadowed_cube.frag"),
            std::vector{kRadianceFormat});
    if (c.settings.ibl())
        ibl_ = std::make_unique<EnvironmentLighting>(c, "scene/deferred_ibl.frag",
                                                     std::vector{kRadianceFormat}, true);
}

void TiledDeferredRenderer::declare(graph::RenderGraph& g, graph::TextureId output,
                                    graph::TextureId depth) {
    gbuffer_.declare(g, ctx_, depth);
    // Multisampled, the culling pass reads every sample, and the clusters' lists are whole (their
    // bounds would hold sample 0's depths only).
    const graph::TextureId lists =
        culling_ ? culling_->declare(g, gbuffer_.depth) : graph::TextureId{};
    tiles_ = lists;
    const ClusterLightGrid::Lists clusterLists = !clusters_ ? ClusterLightGrid::Lists{}
                                                 : gbuffer_.samples > 1
                                                     ? ctx_.clusters->declare(g)
                                                     : ctx_.clusters->declareBounded(g, depth);
    g.addPass(
        clusters_ ? "clustered-lighting" : "tiled-lighting",
        [&](graph::PassBuilder& b) {
            gbuffer_.sampleIn(b, true);
            if (culling_) b.sample(lists);
            if (clusters_) ClusterLightGrid::read(b, clusterLists);
            b.storage(output);
        },
        [this, output, lists](graph::PassContext& pc) {
            if (culling_) {
                culling_->bindFrameAndLights(pc.cmd, (*pipelines_)(frameFeatures(ctx_)));
            } else if (clusters_) {
                bindFrameAndLights(pc.cmd, (*pipelines_)(frameFeatures(ctx_)));
                TileLightCulling::bindLights(pc.cmd, ctx_,
                                             TileLightCulling::lightsFitUniformBlock(ctx_));
                ctx_.clusters->bindLists(pc.cmd);
            } else {
                bindFrameAndLights(pc.cmd, (*pipelines_)(frameFeatures(ctx_)));
            }
            gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, true);
            if (culling_) culling_->bindLists(pc.cmd, pc, lists);
            pc.cmd.setStorageTexture(kSlotRadianceOut, pc.texture(output));
            const RenderSettings& s = ctx_.settings;
            pc.cmd.dispatch((s.width + kTileSize - 1) / kTileSize,
                            (s.height + kTileSize - 1) / kTileSize);
        });
    if (shadowed_)
        shadowed_->declare(
            g,
            [&](graph::PassBuilder& b) {
                gbuffer_.sampleIn(b, true);
                b.colorTarget(output, gdi::LoadOp::Load);
            },
            [this](graph::PassContext& pc) { gbuffer_.bind(pc.cmd, pc, ctx_.pointSampler, true); });
    if (ibl_) ibl_->declare(g, "ibl", gbuffer_, {output});
}

}  // namespace fe::render
