#include "render/ForwardPlusRenderer.h"

#include "render/ClusterLightGrid.h"
#include "render/PostProcess.h"

namespace fe::render {

ForwardPlusRenderer::ForwardPlusRenderer(TechniqueContext& c, Lists lists) : TechniqueRenderer(c) {
    if (lists == Lists::Tiles) culling_ = std::make_unique<TileLightCulling>(c);
    if ((lists == Lists::Clusters || c.settings.msaa > 1) && !c.clusters)
        throw gdi::Error(
            std::string(lists == Lists::Clusters ? "clustered-forward" : "forward-plus") +
            ": the renderer made no light cluster grid");
}

void ForwardPlusRenderer::declare(graph::RenderGraph& g, graph::TextureId output,
                                  graph::TextureId depth) {
    const ForwardTargets t = forwardTargets(g, output, depth);
    MeshPassTargets targets = t.formats;
    // The display image as a second target where the renderer asks for it (displayInShading):
    // cleared as the display pass shows an empty pixel (background 0), written by the shading.
    const graph::TextureId display = culling_ ? ctx_.display : graph::TextureId{};
    if (display.valid()) {
        targets.colorFormats.push_back(kDisplayFormat);
        targets.displayTonemap = uint32_t(ctx_.settings.tonemap);
    }
    // As forward-zprepass: the pre-pass clears the radiance target too (one attachment layout).
    g.addPass(
        "zprepass",
        [&](graph::PassBuilder& b) {
            b.colorTarget(t.color);
            if (display.valid()) b.colorTarget(display, gdi::LoadOp::Clear, {0, 0, 0, 1});
            b.depthTarget(t.depth);
            if (culling_ && t.depth != t.sceneDepth)
                b.resolve(t.depth, t.sceneDepth);  // culling reads one sample
        },
        [this, targets](graph::PassContext& pc) {
            pc.beginRenderPass();
            objects_.clear();
            ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::DepthPrepass, targets,
                               ctx_.frameConstants, ctx_.eye, &objects_);
            pc.cmd.endRenderPass();
        });
    const graph::TextureId tiles =
        culling_ ? culling_->declare(g, t.sceneDepth) : graph::TextureId{};
    tiles_ = tiles;
    // Under MSAA a Forward+ fragment outside its tile's depth bounds walks its cluster's list
    // (fe_forward_pass.glsl), so the grid is built then too. At one sample clustered-forward's
    // opaque fragments stand on the pre-pass's depth: the grid is bounded by it.
    const bool clustersRead = !culling_ || ctx_.settings.msaa > 1;
    ClusterLightGrid::Lists clusters{};
    if (clustersRead)
        clusters = !culling_ && t.depth == t.sceneDepth
                       ? ctx_.clusters->declareBounded(g, t.sceneDepth)
                       : ctx_.clusters->declare(g);
    g.addPass(
        culling_ ? "forward-plus-shading" : "clustered-shading",
        [&](graph::PassBuilder& b) {
            if (culling_) b.sample(tiles);
            if (clustersRead) ClusterLightGrid::read(b, clusters);
            b.colorTarget(t.color, gdi::LoadOp::Load);
            if (display.valid()) b.colorTarget(display, gdi::LoadOp::Load);
            b.depthTarget(t.depth, gdi::LoadOp::Load);
            t.resolveIn(b);
        },
        [this, targets, tiles, clustersRead](graph::PassContext& pc) {
            pc.beginRenderPass();
            if (culling_) culling_->bindLists(pc.cmd, pc, tiles);
            if (clustersRead) ctx_.clusters->bindLists(pc.cmd);
            ctx_.geometry.draw(pc.cmd, ctx_.queue,
                               culling_ ? MeshPass::ForwardTiled : MeshPass::ForwardClustered,
                               targets, ctx_.frameConstants, ctx_.eye, &objects_);
            pc.cmd.endRenderPass();
        });
    declareShadowedForward(g, t, &objects_);
}

}  // namespace fe::render
