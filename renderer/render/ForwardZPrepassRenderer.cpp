#include "render/ForwardZPrepassRenderer.h"

namespace fe::render {

void ForwardZPrepassRenderer::declare(graph::RenderGraph& g, graph::TextureId output,
                                      graph::TextureId depth) {
    const ForwardTargets t = forwardTargets(g, output, depth);
    const MeshPassTargets targets = t.formats;
    // The pre-pass also clears the radiance target (attached, unwritten), so the shading pass
    // loads both and the two passes share one attachment layout and pipeline family.
    g.addPass(
        "zprepass",
        [&](graph::PassBuilder& b) {
            b.colorTarget(t.color);
            b.depthTarget(t.depth);
        },
        [this, targets](graph::PassContext& pc) {
            pc.beginRenderPass();
            objects_.clear();
            ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::DepthPrepass, targets,
                               ctx_.frameConstants, ctx_.eye, &objects_);
            pc.cmd.endRenderPass();
        });
    g.addPass(
        "forward-shading",
        [&](graph::PassBuilder& b) {
            b.colorTarget(t.color, gdi::LoadOp::Load);
            b.depthTarget(t.depth, gdi::LoadOp::Load);
            t.resolveIn(b);
        },
        [this, targets](graph::PassContext& pc) {
            pc.beginRenderPass();
            ctx_.geometry.draw(pc.cmd, ctx_.queue, MeshPass::ForwardEqual, targets,
                               ctx_.frameConstants, ctx_.eye, &objects_);
            pc.cmd.endRenderPass();
        });
    declareShadowedForward(g, t, &objects_);
}

}  // namespace fe::render
