#include "render/ForwardPlusRenderer.h"

namespace fe::render {

ForwardPlusRenderer::ForwardPlusRenderer(TechniqueContext& c) : TechniqueRenderer(c), culling_(c) {}

void ForwardPlusRenderer::declare(graph::RenderGraph& g, graph::TextureId output, graph::TextureId depth) {
    const ForwardTargets t = forwardTargets(g, output, depth);
    const MeshPassTargets targets = t.formats;
    // As forward-zprepass: the pre-pass clears the radiance target too (one attachment layout).
    g.addPass("zprepass", [&](graph::PassBuilder& b) {
        b.colorTarget(t.color);
        b.depthTarget(t.depth);
        if (t.depth != t.sceneDepth) b.resolve(t.depth, t.sceneDepth);  // culling reads one sample
    }, [this, targets](graph::PassContext& pc) {
        pc.beginRenderPass();
        objects_.clear();
        ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::DepthPrepass, targets, ctx_.frameConstants, ctx_.eye, &objects_);
        pc.cmd.endRenderPass();
    });
    const graph::TextureId lists = culling_.declare(g, t.sceneDepth);
    g.addPass("forward-plus-shading", [&](graph::PassBuilder& b) {
        b.sample(lists);
        b.colorTarget(t.color, gdi::LoadOp::Load);
        b.depthTarget(t.depth, gdi::LoadOp::Load);
        t.resolveIn(b);
    }, [this, targets, lists](graph::PassContext& pc) {
        pc.beginRenderPass();
        culling_.bindLists(pc.cmd, pc, lists);
        ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::ForwardTiled, targets, ctx_.frameConstants, ctx_.eye, &objects_);
        pc.cmd.endRenderPass();
    });
    declareShadowedForward(g, t, &objects_);
}

}  // namespace fe::render
